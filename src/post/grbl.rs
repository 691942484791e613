//! The GRBL word-set check: reads a program as GRBL 1.1 would and names the first line it
//! would refuse. Written from GRBL 1.1's documented command list ("Grbl v1.1 Commands": the
//! supported G and M codes, the valid non-command words F I J K L N P R S T X Y Z, one word of
//! a modal group a line, no repeated words, comments in parentheses or after a semicolon, an 80
//! character line buffer). grblHAL reads the same words and more; its check adds the tool
//! change (`M6`) and the tool-length offset by table (`G43 H`).

use super::read::{words, ReadError};

/// Which control reads the program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flavour {
    Grbl11,
    GrblHal,
}

/// Characters GRBL 1.1 keeps of a line (spaces and comments removed), at most.
pub const LINE_BUFFER: usize = 79;

/// G-code groups: one word of each a line.
fn g_group(code: u32, flavour: Flavour) -> Option<&'static str> {
    Some(match code {
        0 | 10 | 20 | 30 | 382..=385 | 800 => "motion",
        40 | 100 | 280 | 281 | 300 | 301 | 530 | 920 | 921 => "non-modal",
        170 | 180 | 190 => "plane",
        200 | 210 => "units",
        900 | 910 => "distance",
        911 => "arc distance",
        930 | 940 => "feed mode",
        400 => "cutter compensation",
        431 | 490 => "tool length offset",
        430 if flavour == Flavour::GrblHal => "tool length offset",
        540..=590 => "coordinate system",
        610 => "control mode",
        _ => return None,
    })
}

fn m_group(code: u32, flavour: Flavour) -> Option<&'static str> {
    Some(match code {
        0 | 1 | 2 | 30 => "stopping",
        3..=5 => "spindle",
        8 | 9 => "coolant",
        // Mist is built into GRBL 1.1 only with ENABLE_M7, off in its default config.h: a
        // default board refuses M7 with error:20.
        7 if flavour == Flavour::GrblHal => "coolant",
        6 if flavour == Flavour::GrblHal => "tool change",
        _ => return None,
    })
}

/// The first line the control would refuse, if any.
pub fn check(text: &str, flavour: Flavour) -> Result<(), ReadError> {
    for (index, raw) in text.lines().enumerate() {
        let err = |message: String| ReadError { line: index + 1, message };
        if raw.trim_start().starts_with('%') {
            return Err(err("GRBL does not read a % line".into()));
        }
        let kept = strip(raw).map_err(err)?;
        if flavour == Flavour::Grbl11 && kept.len() > LINE_BUFFER {
            return Err(err(format!("{} characters without spaces and comments; GRBL's line buffer holds {LINE_BUFFER}", kept.len())));
        }
        let words = words(raw).map_err(err)?;
        let mut seen_groups: Vec<&str> = Vec::new();
        let mut seen_letters: Vec<char> = Vec::new();
        for &(letter, value) in &words {
            match letter {
                'G' | 'M' => {
                    let code = (value * 10.0).round() as u32;
                    let group = if letter == 'G' {
                        g_group(code, flavour)
                    } else if value.fract() == 0.0 {
                        m_group(value as u32, flavour)
                    } else {
                        None
                    };
                    let Some(group) = group else { return Err(err(format!("{letter}{value} is not a command {}", name(flavour)))) };
                    if seen_groups.contains(&group) {
                        return Err(err(format!("two {group} commands on one line")));
                    }
                    seen_groups.push(group);
                }
                'F' | 'I' | 'J' | 'K' | 'L' | 'N' | 'P' | 'R' | 'S' | 'T' | 'X' | 'Y' | 'Z' => {
                    if seen_letters.contains(&letter) {
                        return Err(err(format!("the word {letter} twice on one line")));
                    }
                    seen_letters.push(letter);
                    if letter == 'N' && !(value.fract() == 0.0 && (0.0..=9_999_999.0).contains(&value)) {
                        return Err(err(format!("line number N{value} is not a whole number up to 9999999")));
                    }
                }
                'H' if flavour == Flavour::GrblHal => {}
                other => return Err(err(format!("the word {other} is not one {} reads", name(flavour)))),
            }
        }
        let has = |g: f64| words.iter().any(|&(l, v)| l == 'G' && v == g);
        if has(4.0) && !seen_letters.contains(&'P') {
            return Err(err("a dwell (G4) needs P".into()));
        }
    }
    Ok(())
}

fn name(flavour: Flavour) -> &'static str {
    match flavour {
        Flavour::Grbl11 => "GRBL 1.1",
        Flavour::GrblHal => "grblHAL",
    }
}

/// The line as GRBL keeps it: no spaces, no comments, upper case.
fn strip(line: &str) -> Result<String, String> {
    let mut out = String::new();
    let mut in_comment = false;
    for c in line.chars() {
        match c {
            '(' if in_comment => return Err("a comment inside a comment".into()),
            '(' => in_comment = true,
            ')' if in_comment => in_comment = false,
            ';' if !in_comment => break,
            _ if in_comment => {}
            c if c.is_whitespace() => {}
            c => out.push(c.to_ascii_uppercase()),
        }
    }
    if in_comment {
        return Err("a comment is not closed".into());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grbl_refuses_what_it_cannot_read() {
        let ok = "(title)\nG21\nG90 G94 G17 G91.1\nG54\nS12000 M3\nG0 Z5 ; up\nG1 X1 Y2 Z-1 F300\nG2 X3 Y4 I1 J0 F500\nG4 P1.5\nM5\nM0\nM30\n";
        check(ok, Flavour::Grbl11).unwrap();
        for (text, needle) in [
            ("T2 M6\n", "M6 is not a command"),
            ("G43 H2\n", "G43 is not a command"),
            ("G0 X1 X2\n", "X twice"),
            ("G0 G1 X1\n", "two motion"),
            ("G81 X1 Y1 Z-1 R1\n", "G81"),
            ("%\n", "% line"),
            ("G0 A5\n", "word A"),
            ("G4\n", "needs P"),
            ("M7\n", "M7 is not a command"),
            ("(open\n", "not closed"),
            (&format!("G1 X{} F100\n", "1".repeat(90)), "line buffer"),
        ] {
            let e = check(text, Flavour::Grbl11).unwrap_err();
            assert!(e.to_string().contains(needle), "{text:?}: {e}");
        }
        check("T2 M6\nG43 H2\nM7\n", Flavour::GrblHal).unwrap();
    }
}
