//! Neovim, headless, with the documented configuration (`examples/editors/nvim/turnpass.lua`):
//! the server attaches to `*.min`, `*.nc`, `*.ssb` and `*.sub` buffers and the diagnostics
//! arrive, at the byte columns Neovim computes from the server's UTF-16 ranges; a hover
//! answers; a quick fix chosen from `vim.lsp.buf.code_action()`'s menu edits the right
//! bytes after a multi-byte character and its diagnostic goes; completion after `G7` gives
//! the dialect's cycles as Neovim's omnifunc would list them; the Vim syntax file the
//! configuration puts on the runtime path colours a block's words. Runs when `nvim` is on the PATH (Debian: `apt install neovim`); without it the
//! test is skipped with a banner, and fails under CI, which installs it
//! (`support::external`).

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::support::{external, repo, with_snapshots};

/// The driver: open each program, wait for its diagnostics, record them, hover on `M02`.
const DRIVER: &str = r#"
local out = {}
local dir = os.getenv("TURNPASS_TEST_DIR")
vim.g.turnpass_cmd = { os.getenv("TURNPASS_BIN"), "lsp" }
local function run()
for _, name in ipairs({ "part.min", "part.nc", "part.ssb", "part.sub" }) do
  vim.cmd("edit " .. dir .. "/" .. name)
  local buffer = vim.api.nvim_get_current_buf()
  local arrived = vim.wait(60000, function() return #vim.diagnostic.get(buffer) > 0 end, 50)
  table.insert(out, name .. " (filetype " .. vim.bo.filetype .. ", diagnostics arrived: " .. tostring(arrived) .. ")")
  local list = vim.diagnostic.get(buffer)
  table.sort(list, function(a, b) return a.lnum < b.lnum or (a.lnum == b.lnum and a.col < b.col) end)
  for _, d in ipairs(list) do
    table.insert(out, string.format("  %d:%d-%d:%d severity %d: %s", d.lnum, d.col, d.end_lnum, d.end_col, d.severity, (d.message:gsub("\n", " / "))))
  end
end
local params = { textDocument = { uri = vim.uri_from_bufnr(0) }, position = { line = 3, character = 1 } }
local answers = vim.lsp.buf_request_sync(0, "textDocument/hover", params, 60000) or {}
local hovered = "(nothing)"
for _, answer in pairs(answers) do
  if answer.result then
    hovered = answer.result.contents.value
  end
end
table.insert(out, "hover on M02: " .. hovered)

-- The Vim syntax file's groups (for clients without semantic tokens): each word of line 3.
local groups = {}
for _, column in ipairs({ 1, 5, 6, 10, 11, 13 }) do
  local id = vim.fn.synID(3, column, 1)
  table.insert(groups, vim.fn.getline(3):sub(column, column) .. "=" .. vim.fn.synIDattr(id, "name"))
end
table.insert(out, "syntax of `" .. vim.fn.getline(3) .. "`: " .. table.concat(groups, " "))

-- A quick fix as the user applies it: the cursor on the `O` of `X4O` (byte column 9, after
-- the two-byte `°`), `vim.lsp.buf.code_action()`, the first action chosen in the menu.
vim.ui.select = function(items, _, on_choice)
  for _, item in ipairs(items) do
    table.insert(out, "code action offered: " .. item[2].title)
  end
  on_choice(items[1], 1)
end
local buffer = vim.api.nvim_get_current_buf()
vim.api.nvim_win_set_cursor(0, { 2, 9 })
vim.lsp.buf.code_action()
local fixed = vim.wait(60000, function()
  return vim.api.nvim_buf_get_lines(buffer, 1, 2, false)[1] ~= "(30°) X4O Z-30"
end, 50)
table.insert(out, "after the quick fix (applied: " .. tostring(fixed) .. "): " .. vim.api.nvim_buf_get_lines(buffer, 1, 2, false)[1])
local cleared = vim.wait(60000, function()
  for _, d in ipairs(vim.diagnostic.get(buffer)) do
    if d.lnum == 1 and d.severity == vim.diagnostic.severity.ERROR then return false end
  end
  return true
end, 50)
table.insert(out, "the error on that line is gone: " .. tostring(cleared))

-- Completion as the omnifunc shows it: the server's items for `G7` in the new last line,
-- turned into Vim's complete-items by Neovim's own conversion.
vim.api.nvim_buf_set_lines(buffer, -1, -1, false, { "G7" })
local last = vim.api.nvim_buf_line_count(buffer)
vim.api.nvim_win_set_cursor(0, { last, 2 })
local position = { textDocument = { uri = vim.uri_from_bufnr(buffer) }, position = { line = last - 1, character = 2 } }
local completions = vim.lsp.buf_request_sync(buffer, "textDocument/completion", position, 60000) or {}
for _, answer in pairs(completions) do
  if answer.result then
    for _, item in ipairs(vim.lsp.util.text_document_completion_list_to_complete_items(answer.result, "G7")) do
      table.insert(out, "complete " .. item.word .. " (" .. item.kind .. "): " .. item.menu)
    end
  end
end
end
local ok, problem = pcall(run)
if not ok then
  table.insert(out, "driver failed: " .. tostring(problem))
end
vim.fn.writefile(out, dir .. "/out.txt")
vim.cmd("qa!")
"#;

#[test]
fn neovim_attaches_and_shows_diagnostics() {
    let Some(nvim) = external::program("nvim", "neovim") else { return };
    let dir = tempfile::tempdir().unwrap();
    // An OSP program with OCR damage after a comment holding `°`: Neovim must turn the
    // server's UTF-16 column 8 into byte column 9.
    let program = "$PART.MIN%\n(30°) X4O Z-30\nG01 Z-20 F. }5\nM02\n";
    for name in ["part.min", "part.nc", "part.ssb", "part.sub"] {
        std::fs::write(dir.path().join(name), program).unwrap();
    }
    std::fs::write(dir.path().join("turnpass.toml"), "[machine]\ndialect = \"osp\"\n").unwrap();
    let driver = dir.path().join("driver.lua");
    std::fs::write(&driver, DRIVER).unwrap();
    let mut child = Command::new(nvim)
        .args(["--headless", "--clean", "-n", "-u"])
        .arg(repo().join("examples/editors/nvim/turnpass.lua"))
        .arg("-c")
        .arg(format!("luafile {}", driver.display()))
        .env("TURNPASS_TEST_DIR", dir.path())
        .env("TURNPASS_BIN", env!("CARGO_BIN_EXE_turnpass"))
        .current_dir(dir.path())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Neovim waits for input after an error it cannot report: never wait for it forever.
    let deadline = Instant::now() + Duration::from_secs(300);
    while child.try_wait().unwrap().is_none() {
        if Instant::now() > deadline {
            let _ = child.kill();
            break;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    let output = child.wait_with_output().unwrap();
    let transcript = std::fs::read_to_string(dir.path().join("out.txt")).unwrap_or_else(|_| {
        panic!(
            "Neovim wrote nothing:\n{}\n{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        )
    });
    assert!(!transcript.contains("arrived: false"), "{transcript}");
    with_snapshots("lsp", || insta::assert_snapshot!("neovim-headless", transcript));
}
