//! The command line, driven by the case lists in `tests/cases/commands/` (one file per topic;
//! the cases of all of them run in file order, each with its own snapshot).
//!
//! Besides its arguments and standard input, a case may set environment variables (`env`,
//! `env_remove`; `NO_COLOR=1` is set unless a case says otherwise), give the command a
//! standard stream that is a closed pipe (`closed`: its reader gone before the first write,
//! as under `| head`), no stream at all (`unopened`: as under `>&-`), a full disk (`full`:
//! `/dev/full`, where every write fails for want of space) or a terminal
//! (`terminal`: a pseudo-terminal, whose output is captured), send both streams into one
//! pipe whose reader stops after so many bytes (`cut_after`: as `2>&1 | head -c N`; the
//! snapshot shows what it read), and name outputs that must parse as JSON (`json`:
//! `stdout`, `stderr` or a file under `{tmp}`). In snapshots the escape character shows as
//! `␛`.

use std::collections::BTreeMap;
use std::os::fd::{FromRawFd, OwnedFd};
use std::process::{Command, Stdio};

use serde::Deserialize;

use crate::support::{external, repo, with_snapshots};

#[derive(Deserialize)]
struct Cases {
    case: Vec<Case>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Case {
    name: String,
    args: Vec<String>,
    code: i32,
    #[serde(default)]
    stdin: Option<String>,
    #[serde(default)]
    setup: BTreeMap<String, String>,
    #[serde(default)]
    expect_files: BTreeMap<String, bool>,
    #[serde(default)]
    env: BTreeMap<String, String>,
    #[serde(default)]
    env_remove: Vec<String>,
    #[serde(default)]
    closed: Vec<String>,
    #[serde(default)]
    terminal: Vec<String>,
    /// Standard streams that are not open at all.
    #[serde(default)]
    unopened: Vec<String>,
    /// Standard streams that are `/dev/full`.
    #[serde(default)]
    full: Vec<String>,
    /// Both streams into one pipe whose reader reads this many bytes and goes away.
    #[serde(default)]
    cut_after: Option<usize>,
    #[serde(default)]
    json: Vec<String>,
    /// What the case reads from outside the repository (`support::external`).
    #[serde(default)]
    requires: Vec<Requirement>,
    /// Commands run after `args`, in order, each with its exit code; their output follows
    /// the first command's in the snapshot (to read back what it wrote).
    #[serde(default)]
    then: Vec<Then>,
    /// Commands run first, each of which must exit 0 (their output is not in the snapshot).
    #[serde(default)]
    before: Vec<Vec<String>>,
    /// The umask every command runs under (octal, as `umask` takes it).
    #[serde(default)]
    umask: Option<String>,
    /// Modes (octal) given to files in `{tmp}` after `setup`.
    #[serde(default)]
    setup_modes: BTreeMap<String, String>,
    /// Symbolic links made in `{tmp}` after `setup`: `"link" = "what it names"`.
    #[serde(default)]
    setup_symlinks: BTreeMap<String, String>,
    /// Files in `{tmp}` and the mode (octal permission bits) each must have afterwards.
    #[serde(default)]
    expect_modes: BTreeMap<String, String>,
    /// Links in `{tmp}` that must still be symbolic links naming the same thing afterwards.
    #[serde(default)]
    expect_symlinks: BTreeMap<String, String>,
    /// Files in `{tmp}` that must afterwards hold exactly the bytes of a repository file.
    #[serde(default)]
    expect_contents: BTreeMap<String, String>,
}

#[derive(Deserialize, PartialEq)]
#[serde(rename_all = "lowercase")]
enum Requirement {
    /// The third-party corpus, `../shared/corpus/`.
    Corpus,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Then {
    args: Vec<String>,
    code: i32,
}

/// The binary with `args`, run from the repository root under `umask` when one is given.
fn turnpass(args: &[String], umask: Option<&str>) -> Command {
    let mut command = match umask {
        Some(umask) => {
            let mut shell = Command::new("sh");
            shell.args(["-c", r#"umask "$0" && exec "$@""#, umask, env!("CARGO_BIN_EXE_turnpass")]);
            shell
        }
        None => Command::new(env!("CARGO_BIN_EXE_turnpass")),
    };
    command.args(args).current_dir(repo()).env("NO_COLOR", "1");
    command
}

fn mode_of(path: &std::path::Path) -> String {
    use std::os::unix::fs::PermissionsExt;
    format!("{:o}", std::fs::metadata(path).unwrap().permissions().mode() & 0o7777)
}

/// A pipe: its read end and its write end.
fn open_pipe() -> (OwnedFd, OwnedFd) {
    let mut fds = [0; 2];
    // SAFETY: `pipe` fills both descriptors on success; each is owned exactly once below.
    assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0, "pipe");
    unsafe { (OwnedFd::from_raw_fd(fds[0]), OwnedFd::from_raw_fd(fds[1])) }
}

/// The write end of a pipe whose read end is already closed: every write finds no reader.
fn closed_pipe() -> Stdio {
    let (read, write) = open_pipe();
    drop(read);
    Stdio::from(write)
}

/// A pseudo-terminal: its controller end (read what the command wrote) and the terminal end.
fn pseudo_terminal() -> (std::fs::File, Stdio) {
    let (mut controller, mut terminal) = (0, 0);
    // SAFETY: `openpty` fills both descriptors on success; the name, settings and window size
    // may be null. Each descriptor is owned exactly once below.
    let status = unsafe {
        libc::openpty(&mut controller, &mut terminal, std::ptr::null_mut(), std::ptr::null(), std::ptr::null())
    };
    assert_eq!(status, 0, "openpty");
    let (controller, terminal) = unsafe { (OwnedFd::from_raw_fd(controller), OwnedFd::from_raw_fd(terminal)) };
    (std::fs::File::from(controller), Stdio::from(terminal))
}

/// Everything written to a pseudo-terminal until its last writer closed it (Linux then
/// reports an I/O error rather than the end of the file), with the terminal's CR LF as LF.
fn read_terminal(mut controller: std::fs::File) -> Vec<u8> {
    use std::io::Read;
    let mut bytes = Vec::new();
    let mut buffer = [0; 4096];
    while let Ok(n @ 1..) = controller.read(&mut buffer) {
        bytes.extend_from_slice(&buffer[..n]);
    }
    String::from_utf8_lossy(&bytes).replace("\r\n", "\n").into_bytes()
}

#[test]
fn command_line_cases() {
    let lists = crate::support::case_files(&repo().join("tests/cases/commands"), "toml");
    let mut names = std::collections::BTreeSet::new();
    let cases = lists.iter().flat_map(|path| {
        let cases: Cases = toml::from_str(&std::fs::read_to_string(path).unwrap())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        cases.case
    });
    // Every case runs, and the failing ones are listed at the end.
    let mut failing = Vec::new();
    for case in cases {
        assert!(names.insert(case.name.clone()), "two command cases are named {}", case.name);
        if std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run_case(&case))).is_err() {
            failing.push(case.name);
        }
    }
    assert!(failing.is_empty(), "failing command cases: {failing:?}");
}

/// Run one case: its exit code, files, JSON outputs and snapshot.
fn run_case(case: &Case) {
    let uses_corpus = case.args.iter().any(|a| a.contains("{corpus}"));
    assert_eq!(
        uses_corpus,
        case.requires.contains(&Requirement::Corpus),
        "{}: a case names {{corpus}} in its arguments exactly when it requires the corpus",
        case.name
    );
    let corpus = if uses_corpus {
        match external::corpus_for(&format!("command case `{}`", case.name)) {
            Some(dir) => dir.to_string_lossy().into_owned(),
            None => return,
        }
    } else {
        String::new()
    };
    let tmp = tempfile::tempdir().unwrap();
    let tmp_text = tmp.path().to_string_lossy().into_owned();
    for (from, to) in &case.setup {
        let target = tmp.path().join(to);
        std::fs::create_dir_all(target.parent().unwrap()).unwrap();
        std::fs::copy(repo().join(from), target).unwrap();
    }
    for (file, mode) in &case.setup_modes {
        use std::os::unix::fs::PermissionsExt;
        let mode = u32::from_str_radix(mode, 8).unwrap();
        std::fs::set_permissions(tmp.path().join(file), std::fs::Permissions::from_mode(mode)).unwrap();
    }
    for (link, target) in &case.setup_symlinks {
        std::os::unix::fs::symlink(target, tmp.path().join(link)).unwrap();
    }
    let in_tmp = |args: &[String]| -> Vec<String> {
        args.iter().map(|a| a.replace("{tmp}", &tmp_text).replace("{corpus}", &corpus)).collect()
    };
    for before in &case.before {
        let output = turnpass(&in_tmp(before), case.umask.as_deref()).stdin(Stdio::null()).output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "{}: `{}` failed:\n{stderr}", case.name, before.join(" "));
    }
    let args = in_tmp(&case.args);
    // The snapshot names the temporary folder and the corpus by their placeholders, wherever
    // they are, and the tool's version by its own (it is in every provenance comment; a
    // release must not change them all).
    let placeholders = |text: &str| {
        let text = text.replace(&tmp_text, "{tmp}");
        let text = if corpus.is_empty() { text } else { text.replace(&corpus, "{corpus}") };
        let version = env!("CARGO_PKG_VERSION");
        text.replace(&format!("TURNPASS {version} "), "TURNPASS {version} ")
            .replace(&format!("turnpass {version} "), "turnpass {version} ")
            .replace(&format!("\"version\": \"{version}\""), "\"version\": \"{version}\"")
    };
    let mut command = turnpass(&args, case.umask.as_deref());
    command.envs(&case.env);
    for name in &case.env_remove {
        command.env_remove(name);
    }
    command.stdin(match &case.stdin {
        Some(path) => Stdio::from(std::fs::File::open(repo().join(path)).unwrap()),
        None => Stdio::null(),
    });
    let mut terminals = BTreeMap::new();
    // `2>&1 | head -c N`: one pipe for both streams, read up to N bytes on a thread.
    let mut cut_reader = None;
    if let Some(limit) = case.cut_after {
        let (reader, writer) = open_pipe();
        command.stdout(writer.try_clone().unwrap()).stderr(writer);
        let reader = std::fs::File::from(reader);
        cut_reader = Some(std::thread::spawn(move || {
            use std::io::Read;
            let mut read = Vec::new();
            let _ = reader.take(limit as u64).read_to_end(&mut read);
            read
        }));
    }
    let unopened: Vec<i32> = case
        .unopened
        .iter()
        .map(|s| match s.as_str() {
            "stdout" => 1,
            "stderr" => 2,
            other => panic!("{}: no stream {other}", case.name),
        })
        .collect();
    if !unopened.is_empty() {
        use std::os::unix::process::CommandExt;
        // SAFETY: `close` is async-signal-safe; it runs in the child after its streams are
        // set up, so the command starts with those descriptors not open.
        unsafe {
            command.pre_exec(move || {
                for &fd in &unopened {
                    libc::close(fd);
                }
                Ok(())
            });
        }
    }
    for (stream, set) in
        [("stdout", Command::stdout as fn(&mut Command, Stdio) -> &mut Command), ("stderr", Command::stderr)]
    {
        if case.cut_after.is_some() {
            break;
        }
        let (is_closed, is_terminal) =
            (case.closed.iter().any(|s| s == stream), case.terminal.iter().any(|s| s == stream));
        if is_closed {
            set(&mut command, closed_pipe());
        } else if case.full.iter().any(|s| s == stream) {
            set(&mut command, Stdio::from(std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap()));
        } else if is_terminal {
            let (controller, terminal) = pseudo_terminal();
            set(&mut command, terminal);
            terminals.insert(stream, controller);
        } else {
            set(&mut command, Stdio::piped());
        }
    }
    let child = command.spawn().unwrap();
    // The terminals' other ends are closed only when the command is dropped; they must be,
    // for a read of the terminal to end when the child has exited.
    drop(command);
    let readers: BTreeMap<_, _> =
        terminals.into_iter().map(|(stream, c)| (stream, std::thread::spawn(move || read_terminal(c)))).collect();
    let mut output = child.wait_with_output().unwrap();
    if let Some(reader) = cut_reader {
        output.stdout = reader.join().unwrap();
    }
    for (stream, reader) in readers {
        let bytes = reader.join().unwrap();
        if stream == "stdout" { output.stdout = bytes } else { output.stderr = bytes }
    }
    for target in &case.json {
        let bytes = match target.as_str() {
            "stdout" => output.stdout.clone(),
            "stderr" => output.stderr.clone(),
            file => std::fs::read(tmp.path().join(file)).unwrap_or_default(),
        };
        if let Err(error) = serde_json::from_slice::<serde_json::Value>(&bytes) {
            panic!("{}: {target} is not JSON: {error}\n{}", case.name, String::from_utf8_lossy(&bytes));
        }
    }
    let shown = |bytes: &[u8], stream: &str| {
        let text = progress_bar(&placeholders(&String::from_utf8_lossy(bytes)).replace('\x1b', "␛"));
        if case.closed.iter().any(|s| s == stream) {
            format!("(closed){text}")
        } else if case.unopened.iter().any(|s| s == stream) {
            format!("(not open){text}")
        } else if case.full.iter().any(|s| s == stream) {
            format!("(/dev/full){text}")
        } else if case.cut_after.is_some() && stream == "stderr" {
            "(into standard output's pipe)".to_string()
        } else {
            text
        }
    };
    let stdout = shown(&output.stdout, "stdout");
    let stderr = shown(&output.stderr, "stderr");
    assert_eq!(output.status.code(), Some(case.code), "{}: exit code\nstdout:\n{stdout}\nstderr:\n{stderr}", case.name);
    for (file, present) in &case.expect_files {
        assert_eq!(tmp.path().join(file).exists(), *present, "{}: {file}", case.name);
    }
    for (file, mode) in &case.expect_modes {
        assert_eq!(&mode_of(&tmp.path().join(file)), mode, "{}: the mode of {file}", case.name);
    }
    for (link, target) in &case.expect_symlinks {
        let found = std::fs::read_link(tmp.path().join(link));
        assert_eq!(found.ok(), Some(target.into()), "{}: {link} is a link to {target}", case.name);
    }
    for (file, source) in &case.expect_contents {
        let (found, wanted) =
            (std::fs::read(tmp.path().join(file)).unwrap(), std::fs::read(repo().join(source)).unwrap());
        assert!(found == wanted, "{}: {file} holds other bytes than {source}", case.name);
    }
    // No temporary file may be left behind by a failed write (the ones a case sets up as
    // the leftovers of another run are its own business: `expect_files`).
    let leftovers: Vec<_> = walk(tmp.path())
        .into_iter()
        .filter(|p| {
            p.file_name().is_some_and(|n| {
                let n = n.to_string_lossy();
                (n.starts_with(".tmp") || n.starts_with(".turnpass-")) && !case.setup.values().any(|s| p.ends_with(s))
            })
        })
        .collect();
    assert!(leftovers.is_empty(), "{}: leftovers {leftovers:?}", case.name);
    let mut setting = String::new();
    for (name, value) in &case.env {
        setting.push_str(&format!("{name}={value:?} "));
    }
    for name in &case.env_remove {
        setting.push_str(&format!("(no {name}) "));
    }
    let mut redirects = String::new();
    for stream in &case.closed {
        redirects.push_str(&format!(" ({stream}: a closed pipe)"));
    }
    for stream in &case.terminal {
        redirects.push_str(&format!(" ({stream}: a terminal)"));
    }
    for stream in &case.unopened {
        redirects.push_str(&format!(" ({stream}: not open)"));
    }
    for stream in &case.full {
        redirects.push_str(&format!(" ({stream}: /dev/full)"));
    }
    if let Some(limit) = case.cut_after {
        redirects.push_str(&format!(" 2>&1 | head -c {limit}"));
    }
    let mut text = format!(
        "$ {setting}turnpass {}{redirects}\nexit code: {}\n----- STDOUT\n{stdout}\n----- STDERR\n{stderr}",
        placeholders(&args.join(" ")),
        case.code
    );
    for then in &case.then {
        let args = in_tmp(&then.args);
        let output = turnpass(&args, case.umask.as_deref()).stdin(Stdio::null()).output().unwrap();
        let stdout = placeholders(&String::from_utf8_lossy(&output.stdout));
        let stderr = placeholders(&String::from_utf8_lossy(&output.stderr));
        let shown = placeholders(&args.join(" "));
        assert_eq!(output.status.code(), Some(then.code), "{}: exit code of `{shown}`\n{stderr}", case.name);
        text.push_str(&format!(
            "\n$ turnpass {shown}\nexit code: {}\n----- STDOUT\n{stdout}\n----- STDERR\n{stderr}",
            then.code
        ));
    }
    with_snapshots("cli", || insta::assert_snapshot!(case.name.clone(), text));
}

fn walk(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let path = entry.path();
        if path.is_dir() {
            out.extend(walk(&path));
        } else {
            out.push(path);
        }
    }
    out
}

/// `fmt` with no edits prints every program back byte for byte; a program with errors is
/// printed nowhere (exit 1, nothing on standard output).
#[test]
fn fmt_is_lossless_on_every_case_file() {
    let mut printed = 0;
    for dir in ["tests/cases/parse", "tests/cases/thesis", "examples/programs"] {
        // The settings file beside the example programs is no program.
        for path in walk(&repo().join(dir)).into_iter().filter(|p| p.extension().is_none_or(|e| e != "toml")) {
            let output = Command::new(env!("CARGO_BIN_EXE_turnpass")).arg("fmt").arg(&path).output().unwrap();
            match output.status.code() {
                Some(0) => {
                    assert_eq!(output.stdout, std::fs::read(&path).unwrap(), "{}", path.display());
                    printed += 1;
                }
                Some(1) => assert!(output.stdout.is_empty(), "{}: a program with errors was printed", path.display()),
                code => panic!("{}: exit code {code:?}", path.display()),
            }
        }
    }
    assert!(printed >= 10, "only {printed} programs were printed back");
}

/// A progress bar drawn over itself (`\r[###  ] …`) and cleared at the end (`\r␛[K`) as one
/// token: how often it is redrawn depends on how the threads that measure ran, what it shows
/// does not.
fn progress_bar(text: &str) -> String {
    match (text.find("\r["), text.rfind("\r␛[K")) {
        (Some(first), Some(clear)) if first < clear => {
            format!("{}{{progress bar, drawn and cleared}}{}", &text[..first], &text[clear + "\r␛[K".len()..])
        }
        _ => text.to_string(),
    }
}
