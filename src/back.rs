//! The back end: moves of the IR written as blocks of the program they came from.
//!
//! `grid.rs` takes a length of the IR back to the program's frame, on its least increment,
//! and chooses an arc's words there.
//!
//! The back end decides nothing about which blocks change: `expand` chooses the cycle calls
//! to replace and compensation the segments to write; both write them through here, and
//! the printer (`printer.rs`) puts the new blocks into the program's text.

pub mod grid;
