use super::*;
use crate::diagnostic::DiagnosticKind;

fn at(start: u32, end: u32) -> Diagnostic {
    Diagnostic::warning(DiagnosticKind::UnknownStartPosition, Span::new(start, end))
}

fn spans(list: &SemanticDiagnostics) -> Vec<(u32, u32)> {
    list.iter().map(|d| (d.span.start, d.span.end)).collect()
}

#[test]
fn semantic_diagnostics_follow_edits_in_order() {
    // Reported out of order; kept sorted.
    let mut list = SemanticDiagnostics::new(vec![at(20, 25), at(0, 4), at(10, 12), at(4, 4)]);
    assert_eq!(spans(&list), vec![(0, 4), (4, 4), (10, 12), (20, 25)]);

    // A line break typed at 4: the spans ending there stay (an empty one too), those after
    // move.
    list.move_across_edit(4..4, b"\n\n");
    assert_eq!(spans(&list), vec![(0, 4), (4, 4), (12, 14), (22, 27)]);

    // Bytes 13..16 replaced by one: the span they cross the end of goes, the one after moves
    // back.
    list.move_across_edit(13..16, b"5");
    assert_eq!(spans(&list), vec![(0, 4), (4, 4), (20, 25)]);
    assert_eq!(list.len(), 3);

    // Typed at a span's end on its line: the span grows (a digit at the end of a block);
    // an empty span there stays.
    list.move_across_edit(4..4, b"5");
    assert_eq!(spans(&list), vec![(0, 5), (4, 4), (21, 26)]);

    // A related span moves with the edits, and goes when an edit touches it.
    let mut list = SemanticDiagnostics::new(vec![at(30, 35).with_related(Span::new(2, 5), "here")]);
    list.move_across_edit(0..0, b"X");
    let moved: Vec<Diagnostic> = list.iter().collect();
    assert_eq!(moved[0].span, Span::new(31, 36));
    assert_eq!(moved[0].related[0].0, Span::new(3, 6));
    list.move_across_edit(4..5, b"");
    let moved: Vec<Diagnostic> = list.iter().collect();
    assert_eq!(moved[0].span, Span::new(30, 35));
    assert!(moved[0].related.is_empty());
}

#[test]
fn an_edit_inside_a_diagnostic_stretches_it() {
    // A digit typed inside (10, 20) and one deleted inside it: it stays, its end follows.
    let mut list = SemanticDiagnostics::new(vec![at(10, 20), at(30, 32)]);
    list.move_across_edit(15..15, b"5");
    assert_eq!(spans(&list), vec![(10, 21), (31, 33)]);
    list.move_across_edit(12..14, b"");
    assert_eq!(spans(&list), vec![(10, 19), (29, 31)]);
    // An edit across its end still removes it.
    list.move_across_edit(18..25, b"");
    assert_eq!(spans(&list), vec![(22, 24)]);
}
