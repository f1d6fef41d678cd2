//! Fuzzes covga::fuzz_entry::map_image.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| covga::fuzz_entry::map_image(data));
