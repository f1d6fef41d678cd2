//! Fuzzes covga::fuzz_entry::path_csv.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| covga::fuzz_entry::path_csv(data));
