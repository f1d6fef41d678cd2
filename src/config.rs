//! Configuration errors that name the file, the key or line, the value and what is allowed.

use std::fmt::Display;

/// A bad configuration value or file.
#[derive(Debug, thiserror::Error, PartialEq)]
#[error("{file}: {}{message}", if key.is_empty() { String::new() } else { format!("`{key}` ") })]
pub struct ConfigError {
    /// The file (or a description of the source).
    pub file: String,
    /// Dotted key path, or `line N` for parse errors; empty when not applicable.
    pub key: String,
    /// What is wrong and what is allowed.
    pub message: String,
}

impl ConfigError {
    /// A new error.
    pub fn new(file: impl Display, key: &str, message: impl Into<String>) -> Self {
        Self { file: file.to_string(), key: key.to_string(), message: message.into() }
    }

    /// Condenses a TOML error into one line with its line number.
    pub fn from_toml(file: &str, text: &str, e: &toml::de::Error) -> Self {
        let before = e.span().map(|s| &text[..s.start.min(text.len())]);
        let line = before.map(|b| b.matches('\n').count() + 1);
        let mut message = e.message().replace('\n', " ").trim().to_string();
        if message.is_empty() {
            // The parser gives no words where the text simply ends too early (`planner = `).
            let column = before.map(|b| b.len() - b.rfind('\n').map_or(0, |k| k + 1) + 1);
            message = format!(
                "the TOML is incomplete{}: a value, a closing quote or bracket is missing",
                column.map_or(String::new(), |c| format!(" at column {c}"))
            );
        }
        match line {
            Some(l) => Self::new(format!("{file}:{l}"), "", message),
            None => Self::new(file, "", message),
        }
    }
}

/// Checks `lo ≤ v ≤ hi` and finiteness.
pub fn check_range(file: &str, key: &str, v: f64, lo: f64, hi: f64, allowed: &str) -> Result<(), ConfigError> {
    if v.is_finite() && v >= lo && v <= hi {
        Ok(())
    } else {
        Err(ConfigError::new(file, key, format!("= {} is out of range: allowed {allowed}", crate::io::short_number(v))))
    }
}

/// Checks a probability or fraction in [0, 1].
pub fn check_unit(file: &str, key: &str, v: f64) -> Result<(), ConfigError> {
    check_range(file, key, v, 0.0, 1.0, "[0, 1]")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every TOML error gets words, the one the parser leaves empty (text ending too early)
    /// included.
    #[test]
    fn toml_errors_name_the_line_and_say_what_is_wrong() {
        for (text, line, words) in [
            ("planner = ", "x.toml:1", "incomplete at column 11"),
            ("seed = 1\nplanner = \"thesis", "x.toml:2", "string"),
            ("seed = 1\n[map\n", "x.toml:2", ""),
        ] {
            let e = toml::from_str::<toml::Value>(text).unwrap_err();
            let c = ConfigError::from_toml("x.toml", text, &e);
            assert_eq!(c.file, line, "{text:?}: {c}");
            assert!(!c.message.is_empty() && c.message.contains(words), "{text:?}: {c}");
        }
    }
}
