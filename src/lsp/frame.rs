//! The protocol's framing: `Content-Length: N\r\n\r\n` and N bytes of JSON, read from any
//! byte stream, with every way a frame can be wrong named, and bounded work.
//!
//! A frame whose header cannot be read leaves the stream at an unknown place: the next
//! frame cannot be found, so the connection ends ([`Frame::Broken`]). A frame whose header
//! reads but whose body is not a message (not JSON, not UTF-8, nested beyond serde_json's
//! limit, `{}`, a batch array) is answered and the connection goes on ([`Frame::Invalid`]).
//!
//! **Bounded work.** A header line is at most [`MAX_HEADER_LINE`] bytes and a header at
//! most [`MAX_HEADER_LINES`] lines; a body is at most [`MAX_FRAME_BYTES`] and is read as it
//! arrives, never allocated from the length the client claims (a `Content-Length` of 10¹²
//! is refused, and one of 10⁸ followed by ten bytes holds ten bytes).

use std::io::{BufRead, Read};

use lsp_server::{ErrorCode, Message, RequestId};

/// The largest body the server reads: a program of about 200 MB in a `didOpen`. Larger
/// frames are refused before any of their body is read.
pub const MAX_FRAME_BYTES: u64 = 256 << 20;
/// The longest header line (`Content-Length: …` is 40 bytes at most).
pub const MAX_HEADER_LINE: usize = 1024;
/// The most header lines in one frame (the protocol defines two).
pub const MAX_HEADER_LINES: usize = 32;

/// What one read gave.
#[derive(Debug)]
pub enum Frame {
    /// A message.
    Message(Message),
    /// A frame whose body is no message: answer `code` to `id` (null when it is unknown).
    Invalid { id: Option<RequestId>, code: ErrorCode, message: String },
    /// The stream ended (at a frame boundary, or in the middle of one: the client went away).
    End,
    /// A header that does not read: the stream cannot be followed any further.
    Broken(String),
}

/// Read the next frame.
pub fn read(input: &mut impl BufRead) -> Frame {
    let length = match header(input) {
        Ok(Some(length)) => length,
        Ok(None) => return Frame::End,
        Err(Header::End) => return Frame::End,
        Err(Header::Broken(problem)) => return Frame::Broken(problem),
    };
    let mut body = Vec::new();
    match input.by_ref().take(length).read_to_end(&mut body) {
        Ok(read) if read as u64 == length => decode(&body),
        // The client went away in the middle of a body.
        Ok(_) | Err(_) => Frame::End,
    }
}

enum Header {
    End,
    Broken(String),
}

/// The header's `Content-Length`; `None` when the stream ends before a frame starts.
fn header(input: &mut impl BufRead) -> Result<Option<u64>, Header> {
    let mut length = None;
    for index in 0..=MAX_HEADER_LINES {
        let mut line = Vec::new();
        let read = input
            .by_ref()
            .take(MAX_HEADER_LINE as u64 + 1)
            .read_until(b'\n', &mut line)
            .map_err(|e| Header::Broken(format!("cannot read a header: {e}")))?;
        if read == 0 {
            return if index == 0 { Ok(None) } else { Err(Header::End) };
        }
        if !line.ends_with(b"\n") {
            if line.len() > MAX_HEADER_LINE {
                return Err(Header::Broken(format!("a header line is longer than {MAX_HEADER_LINE} bytes")));
            }
            return Err(Header::End);
        }
        let Some(content) = line.strip_suffix(b"\r\n") else {
            return Err(Header::Broken(format!(
                "header line `{}` ends with a line feed alone; the protocol ends header lines with CR LF",
                shown(&line[..line.len() - 1])
            )));
        };
        if content.is_empty() {
            return match length {
                Some(length) => Ok(Some(length)),
                None => Err(Header::Broken("a frame with no `Content-Length` header".to_string())),
            };
        }
        let Some(colon) = content.windows(2).position(|pair| pair == b": ") else {
            return Err(Header::Broken(format!(
                "malformed header `{}`: a header is `Name: value`, with a space after the colon",
                shown(content)
            )));
        };
        let (name, value) = (&content[..colon], &content[colon + 2..]);
        if name.eq_ignore_ascii_case(b"Content-Length") {
            length = Some(content_length(value)?);
        }
    }
    Err(Header::Broken(format!("a header of more than {MAX_HEADER_LINES} lines")))
}

fn content_length(value: &[u8]) -> Result<u64, Header> {
    let broken = |why: &str| Header::Broken(format!("`Content-Length: {}` {why}", shown(value)));
    if value.is_empty() || !value.iter().all(u8::is_ascii_digit) {
        return Err(broken("is not a byte count"));
    }
    // Twenty digits or fewer fit a u64 up to its last digit; more cannot be a frame.
    let length = std::str::from_utf8(value).ok().and_then(|v| v.parse::<u64>().ok());
    match length {
        Some(length) if length <= MAX_FRAME_BYTES => Ok(length),
        _ => Err(broken(&format!("exceeds the largest frame the server reads, {} MiB", MAX_FRAME_BYTES >> 20))),
    }
}

/// A header's text for a message: printable ASCII, the rest escaped, at most 80 bytes.
fn shown(bytes: &[u8]) -> String {
    let mut text: String = bytes.iter().take(80).flat_map(|&b| std::ascii::escape_default(b)).map(char::from).collect();
    if bytes.len() > 80 {
        text.push('…');
    }
    text
}

/// A body as a message, or what is wrong with it (JSON-RPC 2.0: a body that is not JSON is
/// a parse error, JSON that is not a message an invalid request).
fn decode(body: &[u8]) -> Frame {
    if let Err(error) = std::str::from_utf8(body) {
        let message = format!("not UTF-8: byte {} of the body is not part of a UTF-8 character", error.valid_up_to());
        return Frame::Invalid { id: None, code: ErrorCode::ParseError, message };
    }
    let value: serde_json::Value = match serde_json::from_slice(body) {
        Ok(value) => value,
        Err(error) => {
            return Frame::Invalid { id: None, code: ErrorCode::ParseError, message: format!("not JSON: {error}") };
        }
    };
    let id = value.get("id").and_then(|id| serde_json::from_value::<RequestId>(id.clone()).ok());
    match value {
        serde_json::Value::Array(_) => Frame::Invalid {
            id: None,
            code: ErrorCode::InvalidRequest,
            message: "a batch (a JSON array): the Language Server Protocol sends one message per frame".to_string(),
        },
        value => match serde_json::from_value::<Message>(value) {
            Ok(message) => Frame::Message(message),
            Err(error) => Frame::Invalid {
                id,
                code: ErrorCode::InvalidRequest,
                message: format!("not a request, a response or a notification: {error}"),
            },
        },
    }
}
