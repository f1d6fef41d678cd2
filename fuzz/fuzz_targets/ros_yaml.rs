//! Fuzzes covga::fuzz_entry::ros_yaml.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| covga::fuzz_entry::ros_yaml(data));
