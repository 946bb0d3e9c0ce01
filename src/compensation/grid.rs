//! The least-increment grid a program's coordinates live on.
//!
//! A control accepts coordinates in whole least increments of its program units: 0.001 mm
//! or 0.0001 in, of the diameter on a diameter-programmed lathe (so the radius grid is half
//! the increment). Every point the compensation writes is rounded on this grid from its
//! exact value, never from a rounded neighbour, so rounding errors do not add up along a
//! path; incremental words are differences of rounded absolutes for the same reason.
//!
//! Values are kept as integer counts of the increment (`i64` mantissas with the
//! increment's decimal places), so comparisons and differences are exact.

use crate::semantic::{CoordinateMark, Frame};
use crate::syntax::Number;
use crate::toolpath::Xz;

/// The grid of one stretch of program (a frame and a `G50` shift).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    pub frame: Frame,
    /// Toolpath frame minus program coordinates, mm.
    pub shift: Xz,
    /// Decimal places of the increment in program units.
    pub places: u8,
}

/// A point as the program writes it: `X` (diameter or radius, as programmed) and `Z`, in
/// increments.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct GridPoint {
    pub x: i64,
    pub z: i64,
}

impl Grid {
    pub fn new(mark: &CoordinateMark) -> Grid {
        Grid { frame: mark.frame, shift: mark.shift, places: crate::expand::increment_places(mark.frame.increment) }
    }

    fn scale(&self) -> f64 {
        10f64.powi(i32::from(self.places))
    }

    /// A value in program units to a count of increments.
    pub fn count(&self, value: f64) -> i64 {
        (value * self.scale()).round() as i64
    }

    /// A count of increments as a number to write.
    pub fn number(&self, count: i64) -> Number {
        Number::new(count, self.places, true)
    }

    /// A point of the toolpath frame (mm, X radius), rounded onto the grid.
    pub fn point(&self, p: Xz) -> GridPoint {
        GridPoint {
            x: self.count(self.frame.x_program(p.x - self.shift.x)),
            z: self.count(self.frame.program(p.z - self.shift.z)),
        }
    }

    /// A grid point back in the toolpath frame.
    pub fn to_mm(&self, g: GridPoint) -> Xz {
        let scale = self.scale();
        Xz::new(self.frame.x_mm(g.x as f64 / scale) + self.shift.x, self.frame.mm(g.z as f64 / scale) + self.shift.z)
    }

    /// `p` rounded onto the grid, in the toolpath frame.
    pub fn round(&self, p: Xz) -> Xz {
        self.to_mm(self.point(p))
    }

    /// A length (a radius, an `I`/`K` offset; never a diameter) in mm as a count.
    pub fn length(&self, mm: f64) -> i64 {
        self.count(self.frame.program(mm))
    }

    /// A count of a length back in mm.
    pub fn length_mm(&self, count: i64) -> f64 {
        self.frame.mm(count as f64 / self.scale())
    }

    /// The increment in mm (of X as programmed: the diameter on a diameter machine).
    pub fn increment_mm(&self) -> f64 {
        self.frame.mm(self.frame.increment)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::{DecimalInput, Dialect};

    fn grid(inch: bool, diameter: bool) -> Grid {
        let frame = Frame {
            dialect: Dialect::Fanuc,
            inch,
            diameter,
            decimal_input: DecimalInput::Calculator,
            increment: if inch { 0.0001 } else { 0.001 },
        };
        Grid::new(&CoordinateMark { from_move: 0, frame, absolute: true, shift: Xz::default() })
    }

    #[test]
    fn diameter_grid_is_half_the_increment_in_radius() {
        let g = grid(false, true);
        // 10.00024 mm radius is a diameter of 20.00048: 20.000 on the grid, 10.000 back.
        assert_eq!(g.point(Xz::new(10.00024, 0.0)).x, 20_000);
        assert_eq!(g.point(Xz::new(10.00026, 0.0)).x, 20_001);
        assert!((g.round(Xz::new(10.00026, 0.0)).x - 10.0005).abs() < 1e-12);
    }

    #[test]
    fn inch_grid_rounds_in_inches() {
        let g = grid(true, false);
        let p = g.point(Xz::new(25.4 * 1.00004, -25.4 * 0.00006));
        assert_eq!((p.x, p.z), (10_000, -1));
    }
}
