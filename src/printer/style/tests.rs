//! The tally counts a number as the plain definitions say: below one by comparison with
//! `10u64.pow(scale)`, whole by `Number::is_whole`, whatever the shortcuts it takes.

use proptest::prelude::*;

use super::*;
use crate::dialect::{DialectChoice, GCodeSystem};
use crate::syntax::{ParseOptions, parse};

/// The counts of one number by the definitions, in the tally's order: small without and
/// with a leading zero, the scale counted (if any), with a trailing zero, no point, point
/// only, point and zeros.
fn by_definition(number: Number, is_length: bool) -> (u32, u32, Option<usize>, u32, u32, u32, u32) {
    let below_one = number.has_point()
        && number.mantissa.unsigned_abs() < 10u64.pow(u32::from(number.scale))
        && number.mantissa != 0;
    let without_zero = number.flags.contains(NumberFlags::NO_INTEGER_DIGITS);
    let mut counts = (u32::from(below_one && without_zero), u32::from(below_one && !without_zero), None, 0, 0, 0, 0);
    if is_length {
        if number.has_point() {
            counts.2 = Some((number.scale as usize).min(9));
            counts.3 = u32::from(number.scale > 0 && number.mantissa % 10 == 0);
        }
        if number.is_whole() {
            match (number.has_point(), number.scale) {
                (false, _) => counts.4 = 1,
                (true, 0) => counts.5 = 1,
                (true, _) => counts.6 = 1,
            }
        }
    }
    counts
}

fn counted(tally: &StyleTally) -> (u32, u32, Option<usize>, u32, u32, u32, u32) {
    (
        tally.small_without_zero,
        tally.small_with_zero,
        tally.scales.iter().position(|&c| c > 0),
        tally.with_trailing_zero,
        tally.no_point,
        tally.point_only,
        tally.point_zero,
    )
}

fn number() -> impl Strategy<Value = Number> {
    // Mantissas near powers of ten and with trailing zeros are where the shortcuts decide.
    let mantissa = prop_oneof![
        any::<i64>(),
        (-100_000i64..100_000),
        (0u32..19, -3i64..=3, any::<bool>()).prop_map(|(power, offset, negative)| {
            let m = 10i64.pow(power) + offset;
            if negative { -m } else { m }
        }),
        (-1000i64..1000, 0u32..16).prop_map(|(m, power)| m.saturating_mul(10i64.pow(power))),
    ];
    (mantissa, 0u8..=18, any::<bool>(), any::<bool>()).prop_map(|(mantissa, scale, point, no_integer_digits)| {
        let mut number = Number::new(mantissa, if point { scale } else { 0 }, point);
        if no_integer_digits {
            number.flags.insert(NumberFlags::NO_INTEGER_DIGITS);
        }
        number
    })
}

proptest! {
    #[test]
    fn add_number_counts_by_definition(number in number(), is_length in any::<bool>()) {
        let options = ParseOptions {
            dialect: DialectChoice::Fixed(Dialect::Fanuc),
            gcode_system: GCodeSystem::A,
            machine_kind: None,
            control: Default::default(),
        };
        let parsed = parse(b"", &options);
        let mut tally = StyleTally::new(&parsed.program);
        tally.add_number(number, is_length);
        prop_assert_eq!(counted(&tally), by_definition(number, is_length));
    }
}
