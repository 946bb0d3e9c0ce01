//! What an output is written into (fault tests a case file cannot hold): a regular file is
//! replaced atomically, synced before its rename and its folder after; a character device,
//! a FIFO or standard output is written directly, and stays what it was.

use std::io::Read;
use std::os::fd::{FromRawFd, OwnedFd};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::support::{external, repo};

const PROGRAM: &str = "tests/cases/compensate/face.nc";
const MODEL: &str = "tests/cases/compensate/machine.toml";

fn turnpass() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_turnpass"));
    command.current_dir(repo()).env("NO_COLOR", "1").stdin(Stdio::null());
    command
}

/// The compensated program as `compensate` prints it to a pipe: what every output must hold.
fn compensated() -> Vec<u8> {
    let output = turnpass().args(["compensate", PROGRAM, "--model", MODEL]).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(output.stdout.starts_with(b"%"), "{}", String::from_utf8_lossy(&output.stdout));
    output.stdout
}

/// Run `command`, killed after a minute: a run that waits on a FIFO forever fails here.
fn run_within_a_minute(mut command: Command) -> std::process::Output {
    let mut child = command.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
            let output = child.wait_with_output().unwrap();
            panic!("still running after a minute:\n{}", String::from_utf8_lossy(&output.stderr));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

fn file_type(path: &Path) -> std::fs::FileType {
    std::fs::symlink_metadata(path).unwrap().file_type()
}

/// A FIFO at `path`, and a thread that reads it to its end.
fn fifo_with_reader(path: &Path) -> std::thread::JoinHandle<Vec<u8>> {
    let name = std::ffi::CString::new(path.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: `mkfifo` reads the NUL-terminated name and makes the node.
    assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0, "mkfifo");
    let path = path.to_path_buf();
    std::thread::spawn(move || {
        let mut bytes = Vec::new();
        std::fs::File::open(path).unwrap().read_to_end(&mut bytes).unwrap();
        bytes
    })
}

/// `compensate -o FIFO` writes into the FIFO (a reader gets the program) and the FIFO stays
/// a FIFO; `plot -o FIFO.svg` likewise. Before, compensate's check that the output is not its
/// input opened the FIFO for reading and waited forever, and plot renamed a file over it.
#[test]
fn an_output_onto_a_fifo_is_written_into_it() {
    use std::os::unix::fs::FileTypeExt;
    let tmp = tempfile::tempdir().unwrap();
    let fifo = tmp.path().join("program.nc");
    let reader = fifo_with_reader(&fifo);
    let mut command = turnpass();
    command.args(["compensate", PROGRAM, "--model", MODEL, "-o"]).arg(&fifo);
    let output = run_within_a_minute(command);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(reader.join().unwrap() == compensated(), "the FIFO's reader got another program");
    assert!(file_type(&fifo).is_fifo(), "the FIFO was replaced");

    let fifo = tmp.path().join("plot.svg");
    let reader = fifo_with_reader(&fifo);
    let mut command = turnpass();
    command.args(["plot", PROGRAM, "--model", MODEL, "-o"]).arg(&fifo);
    let output = run_within_a_minute(command);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(reader.join().unwrap().starts_with(b"<svg"), "the FIFO's reader got no plot");
    assert!(file_type(&fifo).is_fifo(), "the FIFO was replaced");
}

/// A pseudo-terminal: its controller end, its terminal end (kept open until the command has
/// written, so that the controller's reads do not end early) and the terminal's path.
fn pseudo_terminal() -> (std::fs::File, OwnedFd, PathBuf) {
    let (mut controller, mut terminal) = (0, 0);
    // SAFETY: `openpty` fills both descriptors on success; name, settings and size may be null.
    let status = unsafe {
        libc::openpty(&mut controller, &mut terminal, std::ptr::null_mut(), std::ptr::null(), std::ptr::null())
    };
    assert_eq!(status, 0, "openpty");
    // SAFETY: both descriptors were just opened and are owned once each.
    let (controller, terminal) = unsafe { (OwnedFd::from_raw_fd(controller), OwnedFd::from_raw_fd(terminal)) };
    let path = std::fs::read_link(format!("/proc/self/fd/{}", std::os::fd::AsRawFd::as_raw_fd(&terminal))).unwrap();
    (std::fs::File::from(controller), terminal, path)
}

/// `-o` naming a character device writes into the device, which stays a device: a terminal
/// (any user can open one) shows the program; as root, a node made like `/dev/null` stays a
/// device. Before, a temporary file was renamed over it (as root, `-o /dev/null` replaced
/// `/dev/null` with a regular file), or, where its folder takes no new file, the run failed.
#[test]
fn an_output_onto_a_character_device_is_written_into_it() {
    use std::os::unix::fs::FileTypeExt;
    let (mut controller, _open, terminal) = pseudo_terminal();
    let output = turnpass().args(["compensate", PROGRAM, "--model", MODEL, "-o"]).arg(&terminal).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(file_type(&terminal).is_char_device(), "{} is no longer a device", terminal.display());
    // The terminal turns LF into CR LF.
    let wanted = String::from_utf8(compensated()).unwrap().replace('\n', "\r\n");
    let mut shown = vec![0; wanted.len()];
    controller.read_exact(&mut shown).unwrap();
    assert_eq!(String::from_utf8_lossy(&shown), wanted);

    // A device node of our own (`mknod` needs root): one that discards what it is given.
    let tmp = tempfile::tempdir().unwrap();
    let node = tmp.path().join("null");
    let name = std::ffi::CString::new(node.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: `mknod` reads the NUL-terminated name; device 1:3 is the null device.
    if unsafe { libc::mknod(name.as_ptr(), libc::S_IFCHR | 0o666, libc::makedev(1, 3)) } == 0 {
        let output = turnpass().args(["compensate", PROGRAM, "--model", MODEL, "-o"]).arg(&node).output().unwrap();
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        assert!(file_type(&node).is_char_device(), "the device node was replaced by a file");
    }
}

/// `-o /dev/stdout` is standard output itself: appended to a file opened with `>>` (the
/// file's earlier contents kept), and written into a pipe. Before, the file was replaced by
/// the program alone, and into a pipe the run failed on a temporary file it tried to make
/// under `/proc/self/fd/`.
#[test]
fn an_output_onto_standard_output_by_name_is_standard_output() {
    let tmp = tempfile::tempdir().unwrap();
    let appended = tmp.path().join("app.nc");
    std::fs::write(&appended, b"(EARLIER PROGRAM)\n").unwrap();
    let status = Command::new("sh")
        .arg("-c")
        .arg(r#"exec "$0" compensate "$1" --model "$2" -o /dev/stdout >> "$3""#)
        .arg(env!("CARGO_BIN_EXE_turnpass"))
        .args([PROGRAM, MODEL])
        .arg(&appended)
        .current_dir(repo())
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .unwrap();
    assert!(status.success());
    let mut wanted = b"(EARLIER PROGRAM)\n".to_vec();
    wanted.extend(compensated());
    assert!(std::fs::read(&appended).unwrap() == wanted, "the earlier contents were lost");

    for name in ["/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"] {
        let output = turnpass().args(["compensate", PROGRAM, "--model", MODEL, "-o", name]).output().unwrap();
        assert!(output.status.success(), "{name}: {}", String::from_utf8_lossy(&output.stderr));
        assert!(output.stdout == compensated(), "{name}: the pipe got another program");
    }
}

/// The atomic replace syncs the temporary file before the rename and the folder after it,
/// so that after a power cut the name never points at a file whose data was not written
/// (traced with strace: the file's `fsync` comes before the `rename`, the folder's after).
/// Before, it renamed with no sync at all.
#[test]
fn an_atomic_write_syncs_the_file_before_its_rename_and_the_folder_after() {
    let Some(strace) = external::program("strace", "strace") else { return };
    let tmp = tempfile::tempdir().unwrap();
    let trace = tmp.path().join("trace.txt");
    let out = tmp.path().join("out.nc");
    let status = Command::new(strace)
        .args(["-f", "-e", "trace=fsync,fdatasync,rename,renameat,renameat2,openat", "-o"])
        .arg(&trace)
        .arg(env!("CARGO_BIN_EXE_turnpass"))
        .args(["compensate", PROGRAM, "--model", MODEL, "-o"])
        .arg(&out)
        .current_dir(repo())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .unwrap();
    assert!(status.success(), "strace or compensate failed");
    assert!(std::fs::read(&out).unwrap() == compensated());
    let trace = std::fs::read_to_string(&trace).unwrap();
    // The descriptor each path was opened as, then the order of the calls.
    let descriptor_of = |wanted: &dyn Fn(&str) -> bool| -> Vec<String> {
        trace
            .lines()
            .filter(|line| line.contains("openat(") && line.split('"').nth(1).is_some_and(wanted))
            .filter_map(|line| line.rsplit("= ").next().map(|fd| fd.trim().to_string()))
            .collect()
    };
    let temporaries = descriptor_of(&|path| path.contains(".turnpass-") && path.ends_with(".partial"));
    let folder = tmp.path().to_string_lossy().into_owned();
    let folders = descriptor_of(&|path| path == folder);
    let position = |wanted: &dyn Fn(&str) -> bool| trace.lines().position(wanted);
    let synced = |fds: &[String], line: &str| {
        fds.iter().any(|fd| line.contains(&format!("fsync({fd})")) || line.contains(&format!("fdatasync({fd})")))
    };
    let rename = position(&|line| line.contains("rename") && line.contains(".partial") && line.contains("out.nc"));
    let file_synced = position(&|line| synced(&temporaries, line));
    let rename = rename.unwrap_or_else(|| panic!("no rename traced:\n{trace}"));
    let file_synced = file_synced.unwrap_or_else(|| panic!("the temporary file was not synced:\n{trace}"));
    assert!(file_synced < rename, "the file was synced after its rename:\n{trace}");
    let folder_synced = trace.lines().skip(rename).position(|line| synced(&folders, line));
    assert!(folder_synced.is_some(), "the folder was not synced after the rename:\n{trace}");
}
