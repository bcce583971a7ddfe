//! Reading a program as `--dialect auto` does, at the reader: the clues' best dialect, and
//! when its reader refuses the program the first other candidate that reads all of it
//! (`DialectGuess::fall_back`), the way the estimate and verify jobs choose.
#![allow(dead_code)]

use millpath::Error;
use millpath::gcode::{DialectChoice, DialectGuess, ReadMove, Reader, ReaderOptions, reads_whole};
use std::path::Path;

/// The choice and what the reader made of the program in that dialect (`opts` gives every
/// other setting).
pub fn auto_read(
    name: Option<&Path>,
    text: &str,
    opts: &ReaderOptions,
) -> (DialectChoice, Result<Vec<ReadMove>, Error>) {
    let guess = DialectGuess::new(name, text);
    let read = |d| {
        Reader::new(text.as_bytes(), opts.clone().with_dialect(d)).collect::<Result<Vec<_>, _>>()
    };
    let first = guess.choice();
    match read(first.dialect) {
        Ok(m) => (first, Ok(m)),
        Err(e) => match guess.fall_back(&e, |d| {
            reads_whole(text.as_bytes(), opts.clone().with_dialect(d))
        }) {
            Some(c) => {
                let r = read(c.dialect);
                (c, r)
            }
            None => (first, Err(e)),
        },
    }
}
