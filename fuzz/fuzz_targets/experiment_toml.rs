//! Fuzzes covga::fuzz_entry::experiment_toml.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| covga::fuzz_entry::experiment_toml(data));
