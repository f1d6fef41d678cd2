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
        let line = e.span().map(|s| text[..s.start.min(text.len())].matches('\n').count() + 1);
        let message = e.message().replace('\n', " ").trim().to_string();
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
