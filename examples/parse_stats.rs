//! Parse a file and print block/word counts and AST sizes (a profiling aid).
#![allow(clippy::disallowed_methods, clippy::unwrap_used)]
use turnpass::dialect::{DialectChoice, GCodeSystem};
use turnpass::syntax::{ParseOptions, parse};

fn main() {
    let path = std::env::args().nth(1).expect("usage: parse_stats FILE");
    let bytes = std::fs::read(&path).unwrap();
    let dialect = match std::env::args().nth(2).as_deref() {
        Some("osp") => DialectChoice::Fixed(turnpass::dialect::Dialect::Osp),
        Some("fanuc") => DialectChoice::Fixed(turnpass::dialect::Dialect::Fanuc),
        _ => DialectChoice::Auto,
    };
    let options = ParseOptions {
        dialect,
        gcode_system: GCodeSystem::A,
        machine_kind: Some(turnpass::dialect::MachineKind::Lathe),
        control: Default::default(),
    };
    let start = std::time::Instant::now();
    let parsed = parse(&bytes, &options);
    let elapsed = start.elapsed();
    let words: usize = parsed.program.blocks().iter().map(|b| parsed.program.words_of(b).len()).sum();
    println!(
        "{} bytes, {} blocks, {} words, {} diagnostics, {:.1} ms, {:.0} MB/s, heap {} bytes ({:.1}/block); sizes: Block {} Word {} Expr {}",
        bytes.len(),
        parsed.program.blocks().len(),
        words,
        parsed.diagnostics.len(),
        elapsed.as_secs_f64() * 1e3,
        bytes.len() as f64 / 1e6 / elapsed.as_secs_f64(),
        parsed.program.heap_bytes(),
        parsed.program.heap_bytes() as f64 / parsed.program.blocks().len() as f64,
        std::mem::size_of::<turnpass::syntax::Block>(),
        std::mem::size_of::<turnpass::syntax::Word>(),
        std::mem::size_of::<turnpass::syntax::Expr>(),
    );
    println!("Diagnostic {} bytes", std::mem::size_of::<turnpass::diagnostic::Diagnostic>());
}
