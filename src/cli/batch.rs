//! `compensate --out-dir DIR`: many programs, one per worker thread at a time, each
//! written atomically into DIR under its own file name when it compensates cleanly.
//!
//! Workers take the next file from a shared counter (`turnpass::parallel::workers`: the work
//! is one independent job per file, nothing a pool crate would add). Messages are printed
//! per file, in the order the files were given, after all are done, so they never
//! interleave; a progress bar shows on standard error while it is a terminal. The exit
//! code is the worst of the files'.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use super::common::{CliError, check_output_dir, write_file};
use super::compensate::{CompensateArgs, FileResult, compensate_file, refuse_overwriting_input, write_report};
use super::streams;

pub fn run(args: &CompensateArgs) -> Result<ExitCode, CliError> {
    let Some(dir) = &args.out_dir else { return Err(CliError::Usage("--out-dir is missing".to_string())) };
    check_output_dir(dir)?;
    let mut names = HashSet::new();
    let mut targets = Vec::new();
    for file in &args.files {
        let Some(name) = file.file_name().filter(|_| file != Path::new("-")) else {
            return Err(CliError::Usage("--out-dir takes program files, not standard input".to_string()));
        };
        if !names.insert(name.to_os_string()) {
            let name = name.to_string_lossy();
            return Err(CliError::Usage(format!(
                "two programs are named {name}: --out-dir would write both to one file"
            )));
        }
        targets.push(dir.join(name));
    }
    // Before any work: an output that would replace an input (DIR is a program's own folder).
    for target in &targets {
        refuse_overwriting_input(&args.files, target, args.force)?;
    }
    let results = in_parallel(&args.files, &targets, |file, target| {
        let mut result = match compensate_file(file, args) {
            Ok(result) => result,
            Err(error) => FileResult::failed(error.exit_code(), error.message()),
        };
        if let Some(output) = result.output.take()
            && let Err(error) = write_file(target, &output)
        {
            result.code = 2;
            result.messages.extend_from_slice(error.message().as_slice());
        }
        result
    });
    let mut reports = Vec::new();
    let mut worst = 0;
    for (result, file) in results.iter().zip(&args.files) {
        streams::err(&result.messages);
        worst = worst.max(result.code);
        reports.push(result.report_entry(&super::common::display_name(file)));
    }
    if args.report.is_some() {
        write_report(args, &reports)?;
    }
    Ok(ExitCode::from(worst))
}

/// Run `job` on every file over the available cores; results in the files' order.
fn in_parallel(
    files: &[PathBuf],
    targets: &[PathBuf],
    job: impl Fn(&Path, &Path) -> FileResult + Sync,
) -> Vec<FileResult> {
    let workers = turnpass::parallel::cores().min(files.len());
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let slots: Vec<Mutex<Option<FileResult>>> = files.iter().map(|_| Mutex::new(None)).collect();
    let progress = streams::stderr_is_terminal();
    turnpass::parallel::workers(workers, || {
        loop {
            let k = next.fetch_add(1, Ordering::Relaxed);
            let (Some(file), Some(target)) = (files.get(k), targets.get(k)) else { break };
            let result = job(file, target);
            if let Some(slot) = slots.get(k)
                && let Ok(mut slot) = slot.lock()
            {
                *slot = Some(result);
            }
            let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
            if progress {
                let total = files.len();
                streams::progress(finished as f64 / total as f64, &format!("{finished}/{total} programs"));
            }
        }
    });
    if progress {
        streams::progress_clear();
    }
    slots
        .into_iter()
        .zip(files)
        .map(|(slot, file)| {
            slot.into_inner().ok().flatten().unwrap_or_else(|| {
                FileResult::failed(2, format!("error: {}: the worker stopped\n", file.display()).into_bytes())
            })
        })
        .collect()
}
