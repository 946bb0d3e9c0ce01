use super::*;

fn made() -> Provenance {
    Provenance {
        version: "0.1.0".to_string(),
        model: "test lathe".to_string(),
        model_sha256: "3e3e70e7fa2c".to_string(),
        table_sha256: None,
        tolerance_mm: 0.0005,
        strategy: Strategy::Auto,
        step_mm: None,
        start_min: 30.0,
        dialect: None,
    }
}

#[test]
fn the_comment_reads_back_as_written() {
    let densify = Provenance { strategy: Strategy::Densify, step_mm: Some(0.254), start_min: 212.5, ..made() };
    let table = Provenance { table_sha256: Some("4f0c9a17be21".to_string()), ..made() };
    let osp = Provenance { dialect: Some(Dialect::Osp), ..made() };
    for provenance in [made(), densify, table, osp] {
        for upper in [false, true] {
            let text = provenance.text(upper);
            let read = Provenance::parse(&text).expect("a provenance comment").expect("it reads");
            let model = if upper { provenance.model.to_ascii_uppercase() } else { provenance.model.clone() };
            assert_eq!(read, Provenance { model, ..provenance.clone() }, "{text}");
        }
    }
}

#[test]
fn the_comment_is_written_in_one_form() {
    assert_eq!(
        made().text(true),
        "TURNPASS 0.1.0 COMPENSATED, MODEL TEST LATHE, SHA256 3E3E70E7FA2C, TOLERANCE 0.0005 MM, STRATEGY AUTO, \
         START 30 MIN"
    );
    let densify = Provenance { strategy: Strategy::Densify, step_mm: Some(0.5), ..made() };
    assert!(densify.text(false).contains("STRATEGY DENSIFY, STEP 0.5 MM, START 30 MIN"));
    // An inch machine's default tolerance, half of 0.0001 in, in mm: no float noise.
    let inch = Provenance { tolerance_mm: 0.0001 * 25.4 / 2.0, ..made() };
    assert!(inch.text(true).contains("TOLERANCE 0.00127 MM"), "{}", inch.text(true));
    // The dialect, where the text alone would read as the other, last.
    let osp = Provenance { dialect: Some(Dialect::Osp), ..made() };
    assert!(osp.text(true).ends_with("START 30 MIN, DIALECT OSP"), "{}", osp.text(true));
}

#[test]
fn a_model_name_keeps_only_what_a_comment_can_hold() {
    assert_eq!(printable_name("Okuma Howa V40R (thesis lathe), Table 6"), "Okuma Howa V40R thesis lathe Table 6");
    assert_eq!(printable_name("a;b%c\u{e9}d"), "a b c d");
    assert_eq!(printable_name("  ()  "), "UNNAMED");
    let long = "Okuma Howa V40R (thesis lathe), Table 6 errors and several other effects";
    assert_eq!(printable_name(long), "Okuma Howa V40R thesis lathe Table 6 errors...");
    assert_eq!(printable_name(&"x".repeat(60)).len(), NAME_MAX);
    // A name that holds what ends the comment or a field still reads back.
    let odd = Provenance { model: "lathe (3), bay 2; night".to_string(), ..made() };
    let read = Provenance::parse(&odd.text(false)).expect("a mark").expect("it reads");
    assert_eq!(read.model, "lathe 3 bay 2 night");
}

#[test]
fn other_comments_are_not_provenance() {
    for text in [
        "FACE AND TURN",
        "turnpass: dialect=osp",
        "TURNPASS COMPENSATED",
        "TURNPASS 0.1.0 EXPANDED, MODEL X",
        "compensated by turnpass",
        "",
    ] {
        assert_eq!(Provenance::parse(text), None, "{text}");
        assert!(!is_mark(format!("({text})").as_bytes()), "{text}");
    }
    assert!(is_mark(format!("({})", made().text(true)).as_bytes()));
    assert!(is_mark(format!(";  {}", made().text(false)).as_bytes()));
}

#[test]
fn a_damaged_comment_is_a_mark_that_says_what_is_wrong() {
    let cases = [
        ("TURNPASS 0.1.0 COMPENSATED", "it has no MODEL field"),
        ("turnpass 9.9 compensated, model m, sha256 12345", "SHA256 `12345` is not 12 or more hex digits"),
        (
            "TURNPASS 0.1.0 COMPENSATED, MODEL M, SHA256 0123456789AB, TOLERANCE ABC MM, STRATEGY AUTO, START 0 MIN",
            "TOLERANCE `ABC MM` is not a number of mm",
        ),
        (
            "TURNPASS 0.1.0 COMPENSATED, MODEL M, SHA256 0123456789AB, TOLERANCE 0.001 MM, STRATEGY ROUND, START 0 MIN",
            "STRATEGY `ROUND` is not a strategy",
        ),
        (
            "TURNPASS 0.1.0 COMPENSATED, MODEL M, SHA256 0123456789AB, TOLERANCE 0.001 MM, STRATEGY AUTO, START 5 S",
            "START `5 S` is not a number of min",
        ),
        (
            "TURNPASS 0.1.0 COMPENSATED, MODEL M, SHA256 0123456789AB, TOLERANCE 0.001 MM, STRATEGY AUTO",
            "it has no START field",
        ),
    ];
    for (text, why) in cases {
        assert_eq!(Provenance::parse(text), Some(Err(why.to_string())), "{text}");
    }
    // A field a later version adds is skipped.
    let later = format!("{}, SPINDLE 3", made().text(true));
    assert!(matches!(Provenance::parse(&later), Some(Ok(_))));
}

#[test]
fn the_model_is_matched_by_its_digest() {
    let digest = model_sha256(b"[machine]\n", [b"x,err\n0,0\n".as_slice()]);
    assert_eq!(digest.len(), 64);
    let made = Provenance { model_sha256: digest[..SHA256_DIGITS].to_string(), ..made() };
    assert!(made.same_model(&digest));
    assert!(made.same_model(&digest.to_ascii_uppercase()));
    assert!(!made.same_model(&model_sha256(b"[machine]\n", [])));
    // The tables are part of the model, and where one text ends and the next begins counts.
    assert_ne!(model_sha256(b"ab", [b"c".as_slice()]), model_sha256(b"a", [b"bc".as_slice()]));
    assert_ne!(model_sha256(b"m", [b"t".as_slice()]), model_sha256(b"m", [b"u".as_slice()]));
    // SHA-256 of the empty text, the standard's test vector.
    assert_eq!(model_sha256(b"", []), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}
