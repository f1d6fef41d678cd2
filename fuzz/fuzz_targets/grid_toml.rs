//! Fuzzes covga::fuzz_entry::grid_toml.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| covga::fuzz_entry::grid_toml(data));
