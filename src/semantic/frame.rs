//! The boundary between program values and the toolpath frame.
//!
//! A program writes lengths in its units (inch or mm), X as a diameter on a
//! diameter-programmed lathe, and on a least-increment Fanuc control a length without a
//! decimal point counts increments. The IR is millimetres with X as a radius. This is the
//! only place those conversions happen on the way in; the back end's grid (`back/grid.rs`)
//! does the reverse on the way out.

use crate::dialect::{AddressKind, DecimalInput, Dialect};
use crate::syntax::Number;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    pub dialect: Dialect,
    pub inch: bool,
    pub diameter: bool,
    pub decimal_input: DecimalInput,
    /// Least input increment in program units (0.001 mm, 0.0001 in).
    pub increment: f64,
}

pub const MM_PER_INCH: f64 = 25.4;

impl Frame {
    /// Switch units (`G20`/`G21`). The least increment follows: controls pair 0.001 mm with
    /// 0.0001 in (and 0.0001 mm with 0.00001 in), one decimal place more in inch.
    pub fn set_inch(&mut self, inch: bool) {
        if inch != self.inch {
            self.increment = if inch { self.increment / 10.0 } else { self.increment * 10.0 };
            self.inch = inch;
        }
    }

    /// Millimetres per program unit.
    pub fn scale(&self) -> f64 {
        if self.inch { MM_PER_INCH } else { 1.0 }
    }

    /// The value of a literal word in program units: on a least-increment Fanuc control a
    /// length or angle without a decimal point counts increments, and so does a feed per
    /// revolution when `feed_counts` (the tables' `[increment_input]` and the feed mode say
    /// so).
    pub fn literal(&self, number: Number, kind: Option<AddressKind>, feed_counts: bool) -> f64 {
        if self.counts_increments(number, kind, feed_counts) {
            number.mantissa as f64 * self.increment
        } else {
            number.to_f64()
        }
    }

    /// Whether a literal word reads as a count of least increments (see [`Frame::literal`]).
    pub fn counts_increments(&self, number: Number, kind: Option<AddressKind>, feed_counts: bool) -> bool {
        self.dialect == Dialect::Fanuc
            && self.decimal_input == DecimalInput::Increment
            && !number.has_point()
            && match kind {
                Some(AddressKind::Length | AddressKind::Angle) => true,
                Some(AddressKind::Feed) => feed_counts,
                _ => false,
            }
    }

    /// A length in program units to mm.
    pub fn mm(&self, value: f64) -> f64 {
        value * self.scale()
    }

    /// An X value as programmed (diameter or radius, program units) to a radius in mm.
    pub fn x_mm(&self, value: f64) -> f64 {
        let radius = if self.diameter { value / 2.0 } else { value };
        radius * self.scale()
    }

    /// A radius in mm back to X as programmed, in program units.
    pub fn x_program(&self, radius_mm: f64) -> f64 {
        let value = radius_mm / self.scale();
        if self.diameter { value * 2.0 } else { value }
    }

    /// A length in mm back to program units.
    pub fn program(&self, mm: f64) -> f64 {
        mm / self.scale()
    }

    /// A feed in program units (per minute or per revolution) to mm.
    pub fn feed_mm(&self, value: f64) -> f64 {
        value * self.scale()
    }

    /// Surface speed in program units (m/min or ft/min) to mm/min.
    pub fn surface_speed_mm_min(&self, value: f64) -> f64 {
        if self.inch { value * 12.0 * MM_PER_INCH } else { value * 1000.0 }
    }
}
