//! G-code: writer with dialects, reader (lexer → modal interpreter → moves).
pub mod five_axis;
