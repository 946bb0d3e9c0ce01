use super::*;

#[test]
fn role_names_are_the_schema_names() {
    assert_eq!(role_name(Role::AllowanceX), "allowance_x");
    assert_eq!(role_name(Role::TypeIi), "type_ii");
    assert_eq!(role_name(Role::DwellMilliseconds), "dwell_milliseconds");
}
