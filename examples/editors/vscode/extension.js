// The VS Code client of `turnpass lsp`: starts the server for lathe programs and passes
// the `turnpass.*` settings as its initializationOptions (and again when they change:
// the server reads `settings.turnpass` of workspace/didChangeConfiguration).
"use strict";

const vscode = require("vscode");
const { LanguageClient, TransportKind } = require("vscode-languageclient/node");

let client;

/** The server's options from the `turnpass.*` settings (unset ones left out). */
function options() {
  const config = vscode.workspace.getConfiguration("turnpass");
  const out = {};
  for (const key of ["dialect", "gcodeSystem", "model", "maxDiagnostics"]) {
    const value = config.get(key);
    if (value !== null && value !== undefined) {
      out[key] = value;
    }
  }
  return out;
}

function activate(context) {
  const command = vscode.workspace.getConfiguration("turnpass").get("path") || "turnpass";
  const server = { command, args: ["lsp"], transport: TransportKind.stdio };
  const clientOptions = {
    documentSelector: [{ scheme: "file", language: "turnpass" }],
    initializationOptions: options(),
    synchronize: { configurationSection: "turnpass" },
  };
  client = new LanguageClient("turnpass", "turnpass", { run: server, debug: server }, clientOptions);
  context.subscriptions.push(client);
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
