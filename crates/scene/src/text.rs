//! Text shown to people — curve and scene names, annotation labels — and the characters
//! it may hold: those every output format carries (SVG's XML 1.0, PDF strings, the
//! viewer's font), so a name read from a scene file can always be drawn and written.

/// Whether `c` may appear in a name or label: not a control character (`U+0000`–`U+001F`,
/// `U+007F`–`U+009F`: XML 1.0 forbids most of them even as character references) and not
/// a Unicode noncharacter (`U+FDD0`–`U+FDEF` and the last two code points of every plane,
/// `U+FFFE`, `U+FFFF`, `U+1FFFE`, …).
#[must_use]
pub fn displayable(c: char) -> bool {
    let u = u32::from(c);
    let control = u < 0x20 || (0x7f..=0x9f).contains(&u);
    let noncharacter = (0xfdd0..=0xfdef).contains(&u) || (u & 0xfffe) == 0xfffe;
    !control && !noncharacter
}

#[cfg(test)]
mod tests {
    use super::displayable;

    #[test]
    fn controls_and_noncharacters_are_refused() {
        for c in [
            '\0',
            '\u{1}',
            '\u{1f}',
            '\t',
            '\n',
            '\u{7f}',
            '\u{9f}',
            '\u{fffe}',
            '\u{ffff}',
            '\u{fdd0}',
            '\u{10ffff}',
            '\u{1fffe}',
        ] {
            assert!(!displayable(c), "{:?}", c);
        }
        for c in [
            'a',
            ' ',
            'é',
            'κ',
            '∈',
            '\u{a0}',
            '\u{fffd}',
            '\u{1f600}',
            '\u{fdcf}',
            '\u{fdf0}',
        ] {
            assert!(displayable(c), "{:?}", c);
        }
    }
}
