//! The plans kept once the stream has passed: by move, in stretches of consecutive moves.
//!
//! A motion block's plans are rewritten in the stream, so after it only a cycle's plans are
//! read (a cycle is written once every move is planned), or every move's for the
//! per-block report. A plan holds its first segments inline, some two hundred bytes: one
//! per move of a 50 MB program was 380 MB kept to the end for nothing.

use std::ops::Range;

use super::MovePlan;

#[derive(Debug, Clone, Default)]
pub struct KeptPlans {
    /// Each stretch's first move and its plans, in move order.
    stretches: Vec<(usize, Vec<MovePlan>)>,
}

impl KeptPlans {
    /// Every move's plan, the first move's first.
    #[cfg(test)]
    pub fn all(plans: Vec<MovePlan>) -> KeptPlans {
        KeptPlans { stretches: vec![(0, plans)] }
    }

    /// Keep the plan of move `index`, which comes after every move kept so far.
    pub fn push(&mut self, index: usize, plan: MovePlan) {
        match self.stretches.last_mut() {
            Some((first, plans)) if *first + plans.len() == index => plans.push(plan),
            _ => self.stretches.push((index, vec![plan])),
        }
    }

    /// The plans of `moves`, when every one of them was kept.
    pub fn get(&self, moves: Range<usize>) -> Option<&[MovePlan]> {
        let k = self.stretches.partition_point(|(first, _)| *first <= moves.start).checked_sub(1)?;
        let (first, plans) = self.stretches.get(k)?;
        plans.get(moves.start.checked_sub(*first)?..moves.end.checked_sub(*first)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toolpath::Xz;

    fn plan(x: f64) -> MovePlan {
        MovePlan {
            start: Xz::new(x, 0.0),
            segments: Default::default(),
            changed: false,
            jumps: 0,
            lead_in: false,
            words: Default::default(),
        }
    }

    #[test]
    fn stretches_answer_for_the_moves_they_hold_and_nothing_else() {
        let mut kept = KeptPlans::default();
        for index in [3, 4, 5, 9, 10] {
            kept.push(index, plan(index as f64));
        }
        let starts = |moves| kept.get(moves).map(|p: &[MovePlan]| p.iter().map(|p| p.start.x).collect::<Vec<_>>());
        assert_eq!(starts(3..6), Some(vec![3.0, 4.0, 5.0]));
        assert_eq!(starts(4..5), Some(vec![4.0]));
        assert_eq!(starts(9..11), Some(vec![9.0, 10.0]));
        assert_eq!(starts(5..10), None);
        assert_eq!(starts(0..2), None);
        assert_eq!(starts(10..12), None);
        assert_eq!(KeptPlans::all(vec![plan(0.0), plan(1.0)]).get(1..2).map(|p| p.len()), Some(1));
    }
}
