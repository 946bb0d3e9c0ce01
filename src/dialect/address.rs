//! Addresses (`X`, `XA`) and codes (`G01`, `G12.1`): the two small value types every word
//! and every dialect table refers to.

use std::fmt;
use std::str::FromStr;

use serde::Deserialize;

/// An address: a letter `A`–`Z`, an OSP two-letter extended address such as `XA`, or a
/// Fanuc comma address such as `,C` (chamfer, corner rounding and angle in a move block).
///
/// Stored as one `u16` so that words stay small: 0–25 are letters, from 26 on a letter pair,
/// from `COMMA_BASE` on a comma and a letter.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Address(u16);

impl Address {
    pub const fn letter(letter: u8) -> Address {
        Address((letter - b'A') as u16)
    }

    pub const fn extended(first: u8, second: u8) -> Address {
        Address(26 + (first - b'A') as u16 * 26 + (second - b'A') as u16)
    }

    /// `,C`, `,R`, `,A`: a comma and a letter.
    pub const fn comma(letter: u8) -> Address {
        Address(COMMA_BASE + (letter - b'A') as u16)
    }

    pub fn is_letter(self) -> bool {
        self.0 < 26
    }

    /// A comma address (`,C`), written with no `=`.
    pub fn is_comma(self) -> bool {
        self.0 >= COMMA_BASE
    }

    /// The letter of a one-letter address.
    pub fn as_letter(self) -> Option<u8> {
        if self.is_letter() { Some(b'A' + self.0 as u8) } else { None }
    }

    /// The address as it is written: one or two bytes.
    pub fn bytes(self) -> ([u8; 2], usize) {
        if self.0 < 26 {
            ([b'A' + self.0 as u8, 0], 1)
        } else if self.is_comma() {
            ([b',', b'A' + (self.0 - COMMA_BASE) as u8], 2)
        } else {
            let pair = self.0 - 26;
            ([b'A' + (pair / 26) as u8, b'A' + (pair % 26) as u8], 2)
        }
    }

    pub fn name(self) -> String {
        let (bytes, len) = self.bytes();
        String::from_utf8_lossy(&bytes[..len]).into_owned()
    }

    pub const A: Address = Address::letter(b'A');
    pub const B: Address = Address::letter(b'B');
    pub const C: Address = Address::letter(b'C');
    pub const D: Address = Address::letter(b'D');
    pub const E: Address = Address::letter(b'E');
    pub const F: Address = Address::letter(b'F');
    pub const G: Address = Address::letter(b'G');
    pub const H: Address = Address::letter(b'H');
    pub const I: Address = Address::letter(b'I');
    pub const J: Address = Address::letter(b'J');
    pub const K: Address = Address::letter(b'K');
    pub const L: Address = Address::letter(b'L');
    pub const M: Address = Address::letter(b'M');
    pub const N: Address = Address::letter(b'N');
    pub const O: Address = Address::letter(b'O');
    pub const P: Address = Address::letter(b'P');
    pub const Q: Address = Address::letter(b'Q');
    pub const R: Address = Address::letter(b'R');
    pub const S: Address = Address::letter(b'S');
    pub const T: Address = Address::letter(b'T');
    pub const U: Address = Address::letter(b'U');
    pub const V: Address = Address::letter(b'V');
    pub const W: Address = Address::letter(b'W');
    pub const X: Address = Address::letter(b'X');
    pub const Y: Address = Address::letter(b'Y');
    pub const Z: Address = Address::letter(b'Z');
}

/// The first comma address: after the 26 letters and the 26 × 26 letter pairs.
const COMMA_BASE: u16 = 26 + 26 * 26;

impl fmt::Debug for Address {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

impl fmt::Display for Address {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

impl FromStr for Address {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.as_bytes() {
            [a] if a.is_ascii_uppercase() => Ok(Address::letter(*a)),
            [a, b] if a.is_ascii_uppercase() && b.is_ascii_uppercase() => Ok(Address::extended(*a, *b)),
            [b',', b] if b.is_ascii_uppercase() => Ok(Address::comma(*b)),
            _ => Err(format!("`{s}` is not an address")),
        }
    }
}

impl<'de> Deserialize<'de> for Address {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let text = String::deserialize(deserializer)?;
        text.parse().map_err(serde::de::Error::custom)
    }
}

/// A G or M code in tenths, so `G12.1` is 121 and `G01` is 10.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Code(pub u16);

impl Code {
    pub const fn whole(number: u16) -> Code {
        Code(number * 10)
    }

    pub fn major(self) -> u16 {
        self.0 / 10
    }

    pub fn minor(self) -> u16 {
        self.0 % 10
    }

    /// The code written the way machinists write it: at least two digits, `G01`, `G12.1`.
    pub fn display(self, letter: char) -> String {
        if self.minor() == 0 {
            format!("{letter}{:02}", self.major())
        } else {
            format!("{letter}{:02}.{}", self.major(), self.minor())
        }
    }

    /// The largest code the tables can hold: three digits and a tenth.
    pub const MAX: u16 = 9999;
}

impl fmt::Debug for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.display('#'))
    }
}

pub(crate) fn parse_code(text: &str) -> Result<(char, Code), String> {
    let mut chars = text.chars();
    let letter = chars.next().ok_or("empty code")?;
    let rest = chars.as_str();
    let (major, minor) = match rest.split_once('.') {
        Some((major, minor)) => (major, minor),
        None => (rest, "0"),
    };
    let major: u16 = major.parse().map_err(|_| format!("bad code `{text}`"))?;
    let minor: u16 = minor.parse().map_err(|_| format!("bad code `{text}`"))?;
    if major > 999 || minor > 9 {
        return Err(format!("code `{text}` out of range"));
    }
    Ok((letter, Code(major * 10 + minor)))
}
