//! A role's unit in words, for hovers, completion and inlay hints.
//!
//! The schemas in `grammar/` give every word of a command its [`Role`];
//! `dialect/roles.rs` says what the role is and in which unit it is written. Units are those
//! of the program as written (the semantic pass converts them in `semantic/frame.rs`).

use crate::dialect::{Dialect, Role};
use crate::machine::{MachineSettings, Units};

pub use crate::dialect::roles::{Unit, describe, short as short_value};

/// The unit in words, for this machine. `increments` says the word counts least increments
/// (a Fanuc length the schema writes without a decimal point, `G76 Q`).
pub fn unit_text(unit: Unit, settings: &MachineSettings, dialect: Dialect, increments: bool) -> String {
    let inch = settings.units == Some(Units::Inch);
    let length = if inch { "inch" } else { "mm" };
    let x_as = if settings.diameter_programming.unwrap_or(true) { "a diameter" } else { "a radius" };
    let increment = settings.least_increment.unwrap_or(if inch { 0.0001 } else { 0.001 });
    match unit {
        Unit::Length | Unit::XLength if increments && dialect == Dialect::Fanuc => {
            format!("least increments of {increment} {length}, no decimal point")
        }
        Unit::Length => length.to_string(),
        Unit::XLength => format!("{length}, X as {x_as}"),
        Unit::Feed => format!("{length} per revolution or per minute, as the feed mode says"),
        Unit::Lead => format!("{length} per revolution"),
        Unit::Angle => "degrees".to_string(),
        Unit::Count => "a count".to_string(),
        Unit::Sequence => "a sequence name".to_string(),
        Unit::Seconds => "seconds".to_string(),
        Unit::Milliseconds => "milliseconds".to_string(),
        Unit::Speed => format!("rpm, or {} under constant surface speed", if inch { "ft/min" } else { "m/min" }),
        Unit::Rpm => "rpm".to_string(),
        Unit::Code => "a selection, no unit".to_string(),
        Unit::Flag => "present to select".to_string(),
    }
}

/// The unit of `address` in `form` in words: the role's, in least increments where the form
/// counts the word and `increments` (it is written without a point), as a diameter where
/// the form says the control reads it as one (the OSP thread cycles' `D`, `U`, `H`).
pub fn word_unit_text(
    form: &crate::dialect::Form,
    address: crate::dialect::Address,
    unit: Unit,
    settings: &MachineSettings,
    dialect: Dialect,
    increments: bool,
) -> String {
    if form.is_diameter(address) && matches!(unit, Unit::Length | Unit::XLength) {
        let length = if settings.units == Some(Units::Inch) { "inch" } else { "mm" };
        return format!("{length}, as a diameter (the depth into the part is half of it)");
    }
    unit_text(unit, settings, dialect, increments && form.counts_without_point(address))
}

/// The role's name as the schemas write it (`allowance_x`).
pub fn role_name(role: Role) -> String {
    let debug = format!("{role:?}");
    let mut name = String::with_capacity(debug.len() + 4);
    for (i, c) in debug.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if i > 0 {
                name.push('_');
            }
            name.push(c.to_ascii_lowercase());
        } else {
            name.push(c);
        }
    }
    name
}

#[cfg(test)]
mod tests;
