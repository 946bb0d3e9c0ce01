//! Threads: the one module that starts them, joins them and passes a panic on, and the one
//! place that says from what size a piece of work is worth a second core ([`Tuning`]).
//!
//! The uses: a long program is parsed in two runs of lines (`syntax`), its arcs are timed
//! beside the interpreter (`semantic`), the compensation streams its pieces through four
//! stages at once (`compensation/program/stream.rs`), `verify`'s measure (and
//! `compensate`'s of what it writes) takes the two programs side by side
//! (`compensation::verify::deviation_watched`), `compensate --out-dir` runs one program per
//! core, and the language server reads its client and runs its semantic passes on threads
//! of their own. Each gives the result one thread gives: the split parse and the arc timer
//! are held to the plain run by tests (named beside their fields of [`Tuning`]); each stage
//! of the stream runs its pieces in path order, and each program's measure is its own. A
//! panic on any thread is a bug, and is passed on to the caller as it was raised. The
//! README's "Performance" section gives what each use takes off the main thread and the
//! commands that measure it.

use std::sync::OnceLock;

/// From what size each use of a second thread runs (see the module documentation). The
/// thresholds are not options of any pass: they change how fast a result comes, never the
/// result.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tuning {
    /// `syntax::parse`: a program of at least this many bytes is parsed in two runs of lines
    /// (`syntax/tests.rs`: two runs joined equal one run, wherever the split).
    pub parse_bytes: usize,
    /// `semantic::lower`: a program of at least this many blocks has its arcs timed on a
    /// second thread while it runs (`semantic/emitter/arc_times/tests.rs`, `tests/it/arc_times.rs`).
    pub arc_times_blocks: usize,
    /// The language server: a document larger than this many bytes has its semantic pass
    /// run on a thread of its own, so that keystrokes are answered while it runs; a smaller
    /// one's runs on the server's loop and comes in the same publish as the parse's
    /// (`lsp/server.rs`; the client's `semanticInlineLimit` overrides it). Where the pass
    /// runs changes when its diagnostics are published, not what they are
    /// (`tests/it/lsp_server.rs`).
    pub lsp_inline_bytes: usize,
    /// `compensation::verify::deviation_watched` (`verify`, and `compensate`'s check of what
    /// it writes): the original and the compensated program are measured side by side for
    /// an original of at least this many moves. Each program's measure is its own, in path
    /// order, whichever thread runs it.
    pub measure_moves: usize,
}

impl Tuning {
    /// The thresholds the measurements support (README, "Performance").
    pub const DEFAULT: Tuning =
        Tuning { parse_bytes: 1 << 20, arc_times_blocks: 20_000, lsp_inline_bytes: 256 << 10, measure_moves: 0 };

    /// Every use on one thread.
    pub const SERIAL: Tuning = Tuning {
        parse_bytes: usize::MAX,
        arc_times_blocks: usize::MAX,
        lsp_inline_bytes: usize::MAX,
        measure_moves: usize::MAX,
    };

    /// The names of the uses, as [`Tuning::with_serial`] takes them.
    pub const USES: [&'static str; 4] = ["parse", "arc_times", "lsp_semantic", "measure"];

    /// This tuning with the use `name` (one of [`Tuning::USES`], or `all`) on one thread;
    /// `None` for an unknown name.
    pub fn with_serial(self, name: &str) -> Option<Tuning> {
        let serial = Tuning::SERIAL;
        let mut tuning = self;
        match name {
            "all" => return Some(serial),
            "parse" => tuning.parse_bytes = serial.parse_bytes,
            "arc_times" => tuning.arc_times_blocks = serial.arc_times_blocks,
            "lsp_semantic" => tuning.lsp_inline_bytes = serial.lsp_inline_bytes,
            "measure" => tuning.measure_moves = serial.measure_moves,
            _ => return None,
        }
        Some(tuning)
    }
}

impl Default for Tuning {
    fn default() -> Tuning {
        Tuning::DEFAULT
    }
}

static TUNING: OnceLock<Tuning> = OnceLock::new();

/// The tuning in force: [`Tuning::DEFAULT`] unless [`set_tuning`] chose another.
pub fn tuning() -> &'static Tuning {
    TUNING.get_or_init(Tuning::default)
}

/// Choose the process's tuning, once, before any work (the binary does, to measure a use
/// on one thread against the same use on two: README, "Performance"). Returns `false`
/// when a tuning was in force already.
pub fn set_tuning(tuning: Tuning) -> bool {
    TUNING.set(tuning).is_ok()
}

/// Run `here` on this thread and `there` on a second one; both results. A panic on either
/// is passed on.
pub fn join<A, B: Send>(here: impl FnOnce() -> A, there: impl FnOnce() -> B + Send) -> (A, B) {
    scope(|scope| {
        let there = scope.spawn(there);
        let here = here();
        (here, there.join())
    })
}

/// [`join`] when `parallel`, else `here` and then `there` on this thread.
pub fn join_if<A, B: Send>(parallel: bool, here: impl FnOnce() -> A, there: impl FnOnce() -> B + Send) -> (A, B) {
    if parallel {
        join(here, there)
    } else {
        let here = here();
        (here, there())
    }
}

/// Threads that may borrow from the caller's stack, all joined before `scope` returns
/// (`std::thread::scope`, with the panic of a thread passed on by [`Handle::join`]).
pub fn scope<'env, R>(body: impl for<'scope> FnOnce(&Scope<'scope, 'env>) -> R) -> R {
    #[expect(clippy::disallowed_methods, reason = "threads start here")]
    std::thread::scope(|scope| body(&Scope(scope)))
}

/// The threads of a [`scope`].
pub struct Scope<'scope, 'env: 'scope>(&'scope std::thread::Scope<'scope, 'env>);

impl<'scope> Scope<'scope, '_> {
    /// Run `work` on a new thread of the scope.
    pub fn spawn<T: Send + 'scope>(&self, work: impl FnOnce() -> T + Send + 'scope) -> Handle<'scope, T> {
        Handle(self.0.spawn(work))
    }
}

/// A thread of a [`scope`].
pub struct Handle<'scope, T>(std::thread::ScopedJoinHandle<'scope, T>);

impl<T> Handle<'_, T> {
    /// Wait for the thread and take its result. No use can fail on any input, so a panic
    /// is a bug: it is passed on as it was raised.
    pub fn join(self) -> T {
        self.0.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    }
}

/// Run `worker` on `count` threads at once (at least one) and wait for all of them: each
/// takes its own jobs, as from a shared counter. A panic on any is passed on.
pub fn workers(count: usize, worker: impl Fn() + Sync) {
    scope(|scope| {
        let worker = &worker;
        let handles: Vec<_> = (0..count.max(1)).map(|_| scope.spawn(worker)).collect();
        handles.into_iter().for_each(Handle::join);
    });
}

/// How many threads can run at once on this machine (one when it cannot be told).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZero::get)
}

/// Run `work` on a thread of its own that outlives the caller (the language server's
/// reader of client messages and its semantic passes, which answer through a channel).
pub fn detach(work: impl FnOnce() + Send + 'static) {
    #[expect(clippy::disallowed_methods, reason = "threads start here")]
    std::thread::spawn(work);
}
