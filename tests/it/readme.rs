//! The README's command summaries against the command line itself: every option each
//! subcommand's `--help` lists is in that subcommand's summary (or in `READ`, the options
//! of every command that reads a program, for the commands whose summary names `READ`).
//! An option added to a command and not to the README fails here, and so does an option the
//! README names that the command does not take.

use std::process::Command;

use crate::support::repo;

/// The long options (and the short one beside each, when it has one) of `turnpass ARGS --help`.
fn options_of(args: &[&str]) -> Vec<(String, Option<String>)> {
    let output = Command::new(env!("CARGO_BIN_EXE_turnpass")).args(args).arg("--help").output().unwrap();
    assert!(output.status.success(), "turnpass {args:?} --help");
    let text = String::from_utf8(output.stdout).unwrap();
    let mut options = Vec::new();
    for line in text.lines() {
        let line = line.trim_start();
        let (short, rest) = match line.strip_prefix('-').filter(|rest| !rest.starts_with('-')) {
            Some(rest) => (Some(format!("-{}", &rest[..1])), rest[1..].trim_start_matches(", ")),
            None => (None, line),
        };
        let Some(long) = rest.strip_prefix("--") else { continue };
        let name: String = long.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '-').collect();
        options.push((format!("--{name}"), short));
    }
    options
}

/// The subcommands `turnpass --help` lists (with `model`'s own), as argument lists.
fn subcommands() -> Vec<Vec<&'static str>> {
    let output = Command::new(env!("CARGO_BIN_EXE_turnpass")).arg("--help").output().unwrap();
    let text = String::from_utf8(output.stdout).unwrap();
    let listed: Vec<String> = text
        .lines()
        .skip_while(|line| !line.starts_with("Commands:"))
        .skip(1)
        .take_while(|line| line.starts_with("  "))
        .filter_map(|line| line.split_whitespace().next().map(str::to_string))
        .filter(|name| name != "help")
        .collect();
    let mut commands: Vec<Vec<&'static str>> = Vec::new();
    for name in listed {
        let name: &'static str = Box::leak(name.into_boxed_str());
        if name == "model" {
            commands.push(vec!["model", "report"]);
        } else {
            commands.push(vec![name]);
        }
    }
    assert!(commands.len() >= 13, "{commands:?}");
    commands
}

/// The README's block of command summaries: the text of each `turnpass NAME …` entry with
/// its continuation lines, and the `READ` block.
fn summaries(readme: &str) -> (Vec<(String, String)>, String) {
    let start = readme.find("## Commands\n\n```sh\n").expect("the README's command summaries");
    let block = &readme[start + "## Commands\n\n```sh\n".len()..];
    let block = &block[..block.find("```").unwrap()];
    let mut entries: Vec<(String, String)> = Vec::new();
    for line in block.lines() {
        if let Some(rest) = line.strip_prefix("turnpass ") {
            let words: Vec<&str> = rest.split_whitespace().collect();
            let name = match words.as_slice() {
                ["model", "report", ..] => "model report".to_string(),
                [first, ..] => first.to_string(),
                [] => continue,
            };
            entries.push((name, line.to_string()));
        } else if let Some((_, text)) = entries.last_mut() {
            text.push('\n');
            text.push_str(line);
        }
    }
    // The options `READ` stands for: the code block after the sentence that says so.
    let read = readme[start..]
        .find("`READ` stands for")
        .map(|at| &readme[start + at..])
        .and_then(|text| text.find("```sh\n").map(|at| &text[at + 6..]))
        .and_then(|text| text.find("```").map(|end| text[..end].to_string()))
        .unwrap_or_default();
    (entries, read)
}

/// Whether `text` names `option` as a word of its own (`--step` is not `--step-deg`).
fn names(text: &str, option: &str) -> bool {
    text.match_indices(option).any(|(at, _)| {
        let next = text[at + option.len()..].chars().next();
        let before = text[..at].chars().next_back();
        !next.is_some_and(|c| c.is_ascii_alphanumeric() || c == '-') && before.is_none_or(|c| c != '-')
    })
}

#[test]
fn the_command_summaries_list_every_option() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    let (entries, read) = summaries(&readme);
    let mut missing = Vec::new();
    for command in subcommands() {
        let name = command.join(" ");
        let Some((_, summary)) = entries.iter().find(|(entry, _)| *entry == name) else {
            missing.push(format!("`turnpass {name}` has no summary"));
            continue;
        };
        let options = options_of(&command);
        // And every option the summary names is one the command takes.
        for word in summary.split(|c: char| !(c.is_ascii_alphanumeric() || c == '-')) {
            if word.starts_with("--") && !options.iter().any(|(long, _)| long == word) {
                missing.push(format!("the summary of `turnpass {name}` names {word}, which it does not take"));
            }
        }
        for (long, short) in options {
            // Every command takes these; the README says so once, below the summaries.
            if ["--help", "--color", "--max-input-mb", "--version"].contains(&long.as_str()) {
                continue;
            }
            let in_summary = names(summary, &long) || short.as_deref().is_some_and(|s| names(summary, s));
            let in_read = summary.contains("[READ]") && names(&read, &long);
            if !in_summary && !in_read {
                missing.push(format!("`turnpass {name}` takes {long}, which its summary does not list"));
            }
        }
    }
    assert!(missing.is_empty(), "README.md, \"Commands\":\n{}", missing.join("\n"));
}
