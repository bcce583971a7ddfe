//! G-code: writer with dialects, reader (lexer → modal interpreter → moves).
