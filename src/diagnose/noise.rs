//! Deterministic normal noise for synthetic measurements (`synth --seed N`) and tests:
//! a xorshift64 generator and the Box–Muller transform. The same seed gives the same
//! noise on every machine and every run, and it needs no dependency: the noise only has
//! to look like a gauge's, not to be cryptographically random.

/// A seeded generator of normal noise.
#[derive(Debug, Clone)]
pub struct Noise(u64);

impl Noise {
    /// A generator for `seed`. Xorshift never leaves zero, so a zero seed is replaced by a
    /// fixed odd constant, and the seed is mixed once so that nearby seeds start far apart.
    pub fn new(seed: u64) -> Noise {
        let mixed = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03;
        Noise(if mixed == 0 { 0x2545_F491_4F6C_DD1D } else { mixed })
    }

    /// Uniform in `[0, 1)`, 53 bits.
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Normal with mean 0 and standard deviation `sigma`.
    pub fn normal(&mut self, sigma: f64) -> f64 {
        let (u, v) = (self.uniform().max(1e-300), self.uniform());
        sigma * (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_noise_has_the_asked_spread_and_repeats_for_a_seed() {
        let mut noise = Noise::new(3);
        let values: Vec<f64> = (0..20_000).map(|_| noise.normal(2.0)).collect();
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let sd = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / values.len() as f64).sqrt();
        assert!(mean.abs() < 0.05 && (sd - 2.0).abs() < 0.05, "{mean} {sd}");
        let mut again = Noise::new(3);
        assert_eq!(again.normal(2.0), values[0]);
        assert_ne!(Noise::new(4).normal(2.0), values[0]);
        assert!(Noise::new(0).uniform() > 0.0);
    }
}
