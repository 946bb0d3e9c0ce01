use super::*;
use crate::geometry::on_circle;

/// A repeatable uniform number in [−1, 1] (a linear congruential generator).
pub(crate) struct Noise(pub(crate) u64);

impl Noise {
    pub(crate) fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

fn arc_points(centre: Xz, radius: f64, from_deg: f64, sweep_deg: f64, n: usize) -> Vec<Xz> {
    (0..n)
        .map(|i| {
            let angle = (from_deg + sweep_deg * i as f64 / (n - 1) as f64).to_radians();
            on_circle(centre, radius, angle)
        })
        .collect()
}

fn noisy(points: &[Xz], amplitude: f64, seed: u64) -> Vec<Xz> {
    let mut noise = Noise(seed);
    points.iter().map(|p| Xz::new(p.x + amplitude * noise.next(), p.z + amplitude * noise.next())).collect()
}

fn assert_circle(found: Circle, centre: Xz, radius: f64, within: f64) {
    assert!(found.centre.distance(centre) <= within, "centre {:?} vs {centre:?}", found.centre);
    assert!((found.radius - radius).abs() <= within, "radius {} vs {radius}", found.radius);
}

#[test]
fn exact_points_give_the_circle_back_whole_short_and_tiny() {
    let cases = [
        (Xz::new(3.0, -7.0), 12.5, 0.0, 359.0, 36),
        (Xz::new(50.0, -20.0), 100.0, 40.0, 10.0, 20),
        (Xz::new(0.2, 0.1), 0.5, 200.0, 5.0, 10),
        // Far from the origin: the moments are taken about the points' mean.
        (Xz::new(1.0e4, -1.0e4), 25.0, -30.0, 90.0, 30),
    ];
    for (centre, radius, from, sweep, n) in cases {
        let points = arc_points(centre, radius, from, sweep, n);
        let algebraic = taubin(&points).unwrap();
        assert_circle(algebraic, centre, radius, 1e-9 * radius.max(1.0) * 10.0);
        assert_circle(fit(&points).unwrap(), centre, radius, 1e-9 * radius.max(1.0) * 10.0);
    }
}

#[test]
fn noisy_full_circle_is_found_to_a_fraction_of_the_noise() {
    let centre = Xz::new(0.0153, 0.0930);
    let points = noisy(&arc_points(centre, 100.0, 0.0, 359.0, 360), 0.005, 7);
    let found = fit(&points).unwrap();
    // 360 points of ±5 µm: the centre and radius are known to about 0.3 µm.
    assert_circle(found, centre, 100.0, 0.002);
}

#[test]
fn geometric_fit_is_no_worse_than_taubin_and_is_the_optimum() {
    // The research notes' case: R 100 mm, a 30° arc, 5 µm noise.
    let points = noisy(&arc_points(Xz::new(10.0, -40.0), 100.0, 60.0, 30.0, 60), 0.005, 11);
    let start = taubin(&points).unwrap();
    let best = fit(&points).unwrap();
    let cost = geometric_cost(&points, &best);
    assert!(cost <= geometric_cost(&points, &start));
    // Every small move of the centre or the radius costs more.
    for epsilon in [1e-7, 1e-5, 1e-3] {
        for (dx, dz, dr) in [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 1.0, 0.0), (1.0, 0.0, -1.0)] {
            for sign in [-1.0, 1.0] {
                let s = sign * epsilon;
                let moved = Circle {
                    centre: Xz::new(best.centre.x + s * dx, best.centre.z + s * dz),
                    radius: best.radius + s * dr,
                };
                assert!(geometric_cost(&points, &moved) > cost, "moving by {s} ({dx}, {dz}, {dr}) lowered the cost");
            }
        }
    }
    // The noise is about what is left.
    let rms = (cost / points.len() as f64).sqrt();
    assert!(rms < 0.005, "rms {rms}");
}

#[test]
fn refinement_from_a_poor_start_reaches_the_same_circle() {
    let centre = Xz::new(-4.0, 8.0);
    let points = noisy(&arc_points(centre, 20.0, 0.0, 120.0, 40), 0.001, 3);
    let best = fit(&points).unwrap();
    let from_afar = refine(&points, Circle { centre: Xz::new(-2.0, 9.0), radius: 15.0 }).unwrap();
    assert_circle(from_afar, best.centre, best.radius, 1e-8);
}

#[test]
fn collinear_coincident_too_few_and_not_numbers_have_no_circle() {
    let line: Vec<Xz> = (0..10).map(|i| Xz::new(1.0 + 0.5 * f64::from(i), 2.0 - f64::from(i))).collect();
    assert_eq!(taubin(&line), None);
    assert_eq!(fit(&line), None);
    assert_eq!(fit(&[Xz::new(1.0, 1.0); 5]), None);
    assert_eq!(fit(&[Xz::new(0.0, 0.0), Xz::new(1.0, 1.0)]), None);
    assert_eq!(fit(&[Xz::new(0.0, 0.0), Xz::new(1.0, 1.0), Xz::new(f64::NAN, 0.0)]), None);
    assert_eq!(refine(&[Xz::new(0.0, 0.0)], Circle { centre: Xz::new(0.0, 1.0), radius: 1.0 }), None);
}
