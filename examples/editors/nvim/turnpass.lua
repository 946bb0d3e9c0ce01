-- turnpass language server for Neovim (0.7 and later).
--
-- Attaches `turnpass lsp` to Okuma and Fanuc lathe programs: *.min, *.nc, *.ssb, *.sub
-- (and their upper-case spellings). Diagnostics appear as you type, with their hint;
-- `K` (or `:lua vim.lsp.buf.hover()`) says what the word under the cursor means in the
-- program's dialect, `gd` (`vim.lsp.buf.definition()`) jumps from `P20`, `G85 N0207`,
-- `GOTO NAT00`, `CALL OSUB` or `M98 P1000` to the block it names (in a program file of the
-- same folder too), `vim.lsp.buf.code_action()` offers the quick fix of a hint (`X4O` →
-- `X40`) and, on Fanuc, renumbering, `vim.lsp.buf.rename()` and `vim.lsp.buf.references()`
-- work on sequence names, `<C-x><C-o>` in insert mode completes G and M codes, cycle words
-- and sequence names (the omnifunc is set), `vim.lsp.buf.signature_help()` shows a cycle's
-- forms, and `:lua vim.lsp.buf.formatting_sync()` (0.7) or `vim.lsp.buf.format()` (0.8+)
-- rewrites the program in `fmt --canonical` form. Colour comes from the syntax file in
-- ../vim (added to the runtime path here); Neovim 0.9 and later also colour with the
-- server's semantic tokens.
--
-- Use it from your init.lua:
--
--     dofile("/path/to/turnpass/examples/editors/nvim/turnpass.lua")
--
-- or copy it there. `turnpass` must be on your PATH, or set `vim.g.turnpass_cmd` to the
-- command (a list) first. Machine settings come from the nearest `turnpass.toml` above the
-- program; `vim.g.turnpass_init_options` (a table) is passed as the server's
-- initializationOptions, e.g. `{ dialect = "osp" }` for programs with no turnpass.toml.

local patterns = { "*.min", "*.nc", "*.ssb", "*.sub", "*.MIN", "*.NC", "*.SSB", "*.SUB" }

local group = vim.api.nvim_create_augroup("turnpass", { clear = true })

-- The Vim syntax file beside this one (../vim/syntax/turnpass.vim), for colour without
-- semantic tokens.
local here = debug.getinfo(1, "S").source:sub(2):match("(.*)/") or "."
vim.opt.runtimepath:append(here .. "/../vim")

vim.api.nvim_create_autocmd({ "BufRead", "BufNewFile" }, {
  group = group,
  pattern = patterns,
  callback = function(args)
    vim.bo[args.buf].filetype = "turnpass"
  end,
})

-- The directory of the nearest turnpass.toml above the file, else the file's directory.
local function root_of(file)
  local directory = vim.fn.fnamemodify(file, ":p:h")
  local found = vim.fn.findfile("turnpass.toml", directory .. ";")
  if found ~= "" then
    return vim.fn.fnamemodify(found, ":p:h")
  end
  return directory
end

local client_id = nil

vim.api.nvim_create_autocmd("FileType", {
  group = group,
  pattern = "turnpass",
  callback = function(args)
    vim.bo[args.buf].omnifunc = "v:lua.vim.lsp.omnifunc"
    local config = {
      name = "turnpass",
      cmd = vim.g.turnpass_cmd or { "turnpass", "lsp" },
      root_dir = root_of(vim.api.nvim_buf_get_name(args.buf)),
      init_options = vim.g.turnpass_init_options,
    }
    if vim.lsp.start then
      -- Neovim 0.8 and later reuse a running client with the same name and root.
      vim.lsp.start(config, { bufnr = args.buf })
      return
    end
    -- Neovim 0.7: one client for every program buffer.
    if client_id == nil or vim.lsp.get_client_by_id(client_id) == nil then
      client_id = vim.lsp.start_client(config)
    end
    if client_id ~= nil then
      vim.lsp.buf_attach_client(args.buf, client_id)
    end
  end,
})
