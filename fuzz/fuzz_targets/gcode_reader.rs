//! The G-code reader over arbitrary bytes, streaming (invalid UTF-8 included) and from text,
//! in every dialect: it must return items or errors, never panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use millpath::gcode::{Dialect, Reader, ReaderOptions, read_str};

fuzz_target!(|data: &[u8]| {
    let Some((&flags, body)) = data.split_first() else {
        return;
    };
    let opts = ReaderOptions {
        dialect: match flags % 4 {
            0 => Dialect::LinuxCnc,
            1 => Dialect::Fanuc,
            2 => Dialect::Sinumerik,
            _ => Dialect::Grbl,
        },
        lenient: flags & 4 != 0,
        block_delete: flags & 8 != 0,
        ..ReaderOptions::default()
    };
    let mut rd = Reader::new(std::io::Cursor::new(body), opts.clone());
    for item in rd.by_ref().take(100_000) {
        let _ = item;
    }
    if let Ok(text) = std::str::from_utf8(body) {
        let _ = read_str(text, opts);
    }
});
