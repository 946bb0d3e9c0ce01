use super::*;

fn decide_text(text: &str) -> Detection {
    decide(text.as_bytes(), None, None)
}

#[test]
fn okuma_header_and_lap_mean_osp() {
    let d = decide_text("$A.MIN%\nN0206 G85 N0207 D7 F0.4 U0.4 W0.1\nN0207 G81\n");
    assert_eq!(d.dialect, Dialect::Osp);
    assert_eq!(d.choice, Choice::Detected);
    assert!(!d.is_conflicted());
}

#[test]
fn two_block_g71_and_packed_words_mean_fanuc() {
    let d = decide_text("O2005(Arc)\nN1M26\nG71U.075R.010\nG71P20Q40U.005W.005F.008\nG3X2.5Z-1.25R1.2498F.008\n");
    assert_eq!(d.dialect, Dialect::Fanuc);
    assert!(d.evidence.iter().any(|e| e.feature == Feature::TwoBlockRoughing));
    assert!(d.evidence.iter().any(|e| e.feature == Feature::ArcRadiusR));
}

#[test]
fn mixed_evidence_is_a_conflict() {
    let d = decide_text("$A.MIN%\n#1=2\n");
    assert!(d.is_conflicted());
}

#[test]
fn nothing_to_go_on_is_the_default() {
    let d = decide_text("G00 X1 Z1\n");
    assert_eq!(d.choice, Choice::Default);
    assert_eq!(d.dialect, Dialect::Fanuc);
}

#[test]
fn machining_centre_evidence_sets_the_kind() {
    let d = decide_text("$OKUMA.SSB%\n(OKUMA OSP5020M)\nT1\nM6\n");
    assert_eq!(d.dialect, Dialect::Osp);
    assert_eq!(d.machine_kind, MachineKind::MachiningCentre);
}

#[test]
fn header_shape() {
    assert!(is_osp_header(b"$BR0137.MIN%"));
    assert!(is_osp_header(b"$FLANGE.MIN% "));
    assert!(!is_osp_header(b"$ G84 XA=60"));
    assert!(!is_osp_header(b"$H2.45 L2 F2"));
}

#[test]
fn turnpass_mark_names_the_dialect_and_decides() {
    // An expanded OSP program whose only OSP evidence was in the cycle it replaced: the mark
    // decides, against the Fanuc evidence of its `R` arcs, with no conflict to warn about.
    let d = decide_text("(TURNPASS 0.1.0 EXPANDED, DIALECT OSP)\nG01 X40. F0.1\nG04 F0.14\nG02 X50. Z-5. R5.\n");
    assert_eq!((d.dialect, d.choice), (Dialect::Osp, Choice::Detected));
    assert!(!d.is_conflicted());
    // In lower case, as a `;` comment, as a field of the provenance comment.
    let d = decide_text("#1=2\n(turnpass 0.1.0 compensated, model m, dialect osp)\n");
    assert_eq!(d.dialect, Dialect::Osp);
    let d = decide_text("$A.MIN%\n; TURNPASS 0.1.0 EXPANDED, DIALECT FANUC\n");
    assert_eq!(d.dialect, Dialect::Fanuc);
    // Another comment naming a dialect is no mark.
    let d = decide_text("(DIALECT OSP)\nG00 X1 Z1\n");
    assert_eq!(d.choice, Choice::Default);
}
