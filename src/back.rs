//! The back end: moves of the IR written as blocks of the program they came from.
//!
//! - `grid.rs` takes a length of the IR back to the program's frame, on its least
//!   increment, and chooses an arc's words there: the one place the IR frame is undone.
//! - `motion.rs` is the one writer of motion blocks: every code from the dialect tables
//!   (`Codes`), every coordinate from the grid, the modal state of blocks written afresh.
//! - `cycle.rs` writes a cycle's moves as explicit blocks, and `thread_pass.rs` a thread
//!   pass as a single-pass cycle block where the control has no thread move.
//! - `thread_lead.rs` writes a thread's lead at the digits the control takes, with the word
//!   that holds it: for a kept cycle's lead word as for a written cycle's thread moves.
//!
//! The back end decides nothing about which blocks change: `expand` chooses the cycle calls
//! to replace, and compensation (`compensation/rewrite.rs`) the cycles to expand and the
//! segments of each motion block; both write them through here, in the program's one
//! style (`printer::ProgramStyle`), and the printer puts the new blocks into the
//! program's text.

mod cycle;
pub(crate) mod grid;
pub(crate) mod motion;
pub(crate) mod thread_lead;

pub(crate) use cycle::{Axes, CycleBlocks, carried_words, carry_traced, cycle_blocks};
