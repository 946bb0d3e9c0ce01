//! A thread's lead written at the digits the control takes (`[thread_lead]` in `grammar/`):
//! the one place a corrected lead becomes words, for a kept thread cycle's lead word and a
//! plain thread move's (`compensation/rewrite/cycles.rs::thread_lead`) as for the thread
//! moves of a cycle written out (`cycle.rs`, which takes the words as data per move).
//!
//! The lead word takes the least increment's decimals and the table's `decimals_beyond_increment`
//! more. Where rounding to them leaves more than half an increment over the thread's turns,
//! the lead is written with the dialect's precise-lead word (Fanuc-compatible `E`, two
//! decimals more) or as the length of several threads over their count (OSP `F` over `J`).
//! Where the dialect has neither, the rounded lead is written and `unheld_mm` says how far it
//! runs off over the thread: the caller says so.

use smallvec::SmallVec;

use crate::dialect::Address;
use crate::dialect::tables::ThreadLead;
use crate::syntax::Number;

use super::grid::Grid;

/// The words a lead is written with, and what they give.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct WrittenLead {
    /// The lead word (`F2.`), a precise-lead word instead (`E1.9998`), or the lead word and a
    /// count of threads after it (`F29.997 J20`).
    pub words: SmallVec<[(Address, Number); 2]>,
    /// The lead per thread the words give, program units.
    pub lead: f64,
    /// How far the lead the words give runs from the one wanted over the thread's turns, mm,
    /// where that is more than half an increment (no word of the dialect holds the lead).
    pub unheld_mm: Option<f64>,
}

/// The lead as it is written now: the lead word at `address` (the lead word or the precise
/// one) giving `written` (program units), over `count` threads when the block writes a count
/// of threads (`None`: one).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ProgrammedLead {
    pub address: Address,
    pub written: f64,
    pub count: Option<f64>,
}

/// The words that write the lead `exact` (per thread, program units; the programmed one times
/// the slide's correction) for a thread `thread_mm` long, on `grid`, where the program writes
/// `programmed`; `None` where the lead is not positive.
pub(crate) fn written_lead(
    table: &ThreadLead,
    grid: &Grid,
    programmed: ProgrammedLead,
    exact: f64,
    thread_mm: f64,
) -> Option<WrittenLead> {
    let count = programmed.count.unwrap_or(1.0);
    let lead_mm = grid.frame.mm(programmed.written / count);
    if !(lead_mm > 0.0 && exact > 0.0 && exact.is_finite()) {
        return None;
    }
    let turns = thread_mm / lead_mm;
    let half_increment = grid.length_mm(1) / 2.0;
    // The lead word's value is the length of `count` threads.
    let exact_word = exact * count;
    // The lead a word gives, per thread, and how far its error runs over the thread's turns.
    let drift = |lead: f64| drift_mm(grid, lead, exact, turns);
    // A lead written with the precise-lead word already takes that word's digits.
    let beyond = match table.precise {
        Some(precise) if precise.address == programmed.address => precise.decimals_beyond_increment,
        _ => table.decimals_beyond_increment,
    };
    let places = grid.places.saturating_add(beyond);
    let plain = rounded(exact_word, places);
    let mut words: SmallVec<[(Address, Number); 2]> = smallvec::smallvec![(programmed.address, plain)];
    let mut lead = plain.to_f64() / count;
    if drift(lead) > half_increment {
        if let Some(precise) = table.precise.filter(|_| programmed.count.is_none()) {
            let value = rounded(exact, grid.places.saturating_add(precise.decimals_beyond_increment));
            words = smallvec::smallvec![(precise.address, value)];
            lead = value.to_f64();
        } else if let Some(count_address) = table.count.filter(|_| programmed.count.is_none()) {
            let threads = turns.floor().max(1.0);
            let value = rounded(exact * threads, places);
            words = smallvec::smallvec![(programmed.address, value), (count_address, whole(threads))];
            lead = value.to_f64() / threads;
        }
    }
    let unheld_mm = Some(drift(lead)).filter(|&d| d > half_increment);
    Some(WrittenLead { words, lead, unheld_mm })
}

/// A variable lead's change word (`E` of OSP `G34`, `K` of Fanuc `G34`) written as `old`,
/// for the change `exact` (program units per turn): at the digits it is written with, or the
/// grid's where those are fewer; `None` where that gives `old` back or lies farther from
/// `exact` than `old` does (the slide's correction is finer than the word's digits).
pub(crate) fn written_change(grid: &Grid, old: Number, exact: f64) -> Option<Number> {
    if !exact.is_finite() {
        return None;
    }
    let value = rounded(exact, grid.places.max(old.scale));
    let closer = (value.to_f64() - exact).abs() < (old.to_f64() - exact).abs();
    (value.to_f64() != old.to_f64() && closer).then_some(value)
}

/// How far a thread `thread_mm` long cut at the lead the program writes (`programmed`) runs
/// from one cut at `exact` (per thread, program units), mm, where that is more than half an
/// increment; none where the lead as written holds (`written_lead` would round to it, or
/// to a lead no better over the thread).
pub(crate) fn written_drift_mm(grid: &Grid, programmed: ProgrammedLead, exact: f64, thread_mm: f64) -> Option<f64> {
    let lead = programmed.written / programmed.count.unwrap_or(1.0);
    let lead_mm = grid.frame.mm(lead);
    let drift = drift_mm(grid, lead, exact, thread_mm / lead_mm);
    (drift.is_nan() || drift > grid.length_mm(1) / 2.0).then_some(drift)
}

/// How far a lead `lead` runs from `exact` (per thread, program units) over `turns`, mm.
fn drift_mm(grid: &Grid, lead: f64, exact: f64, turns: f64) -> f64 {
    grid.frame.mm((lead - exact).abs()) * turns
}

/// The words as a program spells them (`E1.9998`, `F33.997 J17`).
pub(crate) fn spelled(words: &[(Address, Number)]) -> String {
    words
        .iter()
        .map(|(a, n)| format!("{}{}", a.name(), crate::syntax::spelling::plain(*n)))
        .collect::<Vec<_>>()
        .join(" ")
}

/// `value` at `places` decimals, with a decimal point and no trailing zeros.
fn rounded(value: f64, places: u8) -> Number {
    let mut mantissa = (value * 10f64.powi(i32::from(places))).round() as i64;
    let mut scale = places;
    while scale > 0 && mantissa % 10 == 0 {
        mantissa /= 10;
        scale -= 1;
    }
    Number::new(mantissa, scale, true)
}

fn whole(value: f64) -> Number {
    Number::new(value as i64, 0, false)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::tables::PreciseLead;

    fn grid() -> Grid {
        let frame = crate::semantic::Frame {
            dialect: crate::dialect::Dialect::Fanuc,
            inch: false,
            diameter: true,
            decimal_input: crate::dialect::DecimalInput::Calculator,
            increment: 0.001,
        };
        Grid::of(frame, crate::toolpath::Xz::default())
    }

    fn spelled(lead: &WrittenLead) -> String {
        super::spelled(&lead.words)
    }

    #[test]
    fn a_lead_the_plain_word_cannot_hold_takes_the_precise_word_or_a_count_or_says_it_is_unheld() {
        let fanuc = ThreadLead {
            decimals_beyond_increment: 0,
            precise: Some(PreciseLead { address: Address::E, decimals_beyond_increment: 2 }),
            count: None,
            continuous: true,
            change: Some(Address::K),
        };
        let osp = ThreadLead {
            decimals_beyond_increment: 0,
            precise: None,
            count: Some(Address::J),
            continuous: false,
            change: None,
        };
        let neither = ThreadLead::default();
        let programmed = ProgrammedLead { address: Address::F, written: 2.0, count: None };
        // 100 ppm short over a 34 mm thread: 3.4 µm, more than half the 1 µm increment.
        let exact = 2.0 * (1.0 - 100e-6);
        let fanuc_lead = written_lead(&fanuc, &grid(), programmed, exact, 34.0).unwrap();
        assert_eq!((spelled(&fanuc_lead).as_str(), fanuc_lead.unheld_mm), ("E1.9998", None));
        let osp_lead = written_lead(&osp, &grid(), programmed, exact, 34.0).unwrap();
        assert_eq!((spelled(&osp_lead).as_str(), osp_lead.unheld_mm), ("F33.997 J17", None));
        let rounded = written_lead(&neither, &grid(), programmed, exact, 34.0).unwrap();
        assert_eq!(spelled(&rounded), "F2.");
        assert!(rounded.unheld_mm.is_some_and(|mm| (mm - 0.0034).abs() < 1e-6), "{rounded:?}");
        // Over a short thread the plain word holds it.
        let short = written_lead(&fanuc, &grid(), programmed, exact, 4.0).unwrap();
        assert_eq!((spelled(&short).as_str(), short.unheld_mm), ("F2.", None));
    }

    #[test]
    fn a_lead_change_is_written_at_its_own_digits_only_where_they_hold_the_correction_better() {
        let written = |mantissa: i64, scale: u8| Number::new(mantissa, scale, true);
        // `E0.02` 100 ppm short is 0.019998: three decimals give 0.020 back, no change.
        assert_eq!(written_change(&grid(), written(2, 2), 0.02 * (1.0 - 100e-6)), None);
        // `K0.5` 2000 ppm short is 0.499, which three decimals hold.
        let change = written_change(&grid(), written(5, 1), 0.5 * (1.0 - 2000e-6)).unwrap();
        assert_eq!(super::spelled(&[(Address::K, change)]), "K0.499");
        // A change written with more decimals than the increment keeps them: `E0.01234`.
        let change = written_change(&grid(), written(1234, 5), 0.01234 * (1.0 + 1000e-6)).unwrap();
        assert_eq!(super::spelled(&[(Address::E, change)]), "E0.01235");
    }
}
