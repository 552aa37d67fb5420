//! A RIB file's bytes as text for the lexer: UTF-8, with every byte that is not part of a
//! UTF-8 character kept as a stand-in character (`U+10FF00 + byte`, in a private use area)
//! instead of `U+FFFD`, so the lexer can name the byte that binary RIB starts with.

/// The first stand-in character: byte `b` is `STAND_IN + b`.
const STAND_IN: u32 = 0x10_FF00;

/// `bytes` as text, bytes that are not UTF-8 kept as stand-ins.
pub fn decode(bytes: &[u8]) -> String {
    let mut text = String::with_capacity(bytes.len());
    for chunk in bytes.utf8_chunks() {
        text.push_str(chunk.valid());
        text.extend(chunk.invalid().iter().map(|&b| stand_in(b)));
    }
    text
}

fn stand_in(b: u8) -> char {
    char::from_u32(STAND_IN + u32::from(b)).unwrap_or(char::REPLACEMENT_CHARACTER)
}

/// The byte of the file that character `c` starts with.
pub fn first_byte(c: char) -> u8 {
    match u32::from(c).checked_sub(STAND_IN) {
        Some(b) => u8::try_from(b).unwrap_or(0xff),
        None => c.encode_utf8(&mut [0; 4]).as_bytes()[0],
    }
}

/// `c` as a string's character: a stand-in is the replacement character `U+FFFD`.
pub fn shown(c: char) -> char {
    if u32::from(c) >= STAND_IN {
        char::REPLACEMENT_CHARACTER
    } else {
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_that_are_not_utf8_keep_their_value() {
        let text = decode(b"a\x89\xffb\xc3\xa9");
        let bytes: Vec<u8> = text.chars().map(first_byte).collect();
        assert_eq!(bytes, [b'a', 0x89, 0xff, b'b', 0xc3]);
        let shown: String = text.chars().map(shown).collect();
        assert_eq!(shown, "a\u{fffd}\u{fffd}bé");
    }

    #[test]
    fn a_byte_order_mark_starts_with_0xef() {
        assert_eq!(first_byte('\u{feff}'), 0xef);
    }
}
