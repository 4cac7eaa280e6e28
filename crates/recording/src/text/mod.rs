//! The delimited-text table parser behind every text reader of the crate: lines and
//! fields ([`lines`]), numbers ([`number`]), one row ([`rows`]), the table and its format
//! ([`table`]), the parser that fills it ([`parser`]), the row → line table
//! ([`line_table`]) and the streaming of a file ([`stream`]). It knows tables of named numeric columns, not what a column means: the
//! lab formats (module `lab`) build on it.

pub(crate) mod line_table;
pub(crate) mod lines;
pub(crate) mod number;
pub(crate) mod parser;
pub(crate) mod rows;
pub(crate) mod stream;
pub(crate) mod table;
