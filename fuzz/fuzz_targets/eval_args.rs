//! Fuzzes covga::fuzz_entry::eval_args.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| covga::fuzz_entry::eval_args(data));
