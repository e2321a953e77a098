//! Input and output: atomic files and the signal cleanup ([`files`]), CSV and tables
//! ([`table`]), JSON ([`json`]), the progress bar ([`progress`]). Depends on
//! [`crate::error`] only; every command writes through it.

pub mod files;
pub mod json;
pub mod progress;
pub mod table;

pub use files::{stdout_write, write_atomic, DirLock, Stream, Temporary, TemporaryDir};
pub use json::{emit, jlimit, jnum, jvec, params_json, pretty};
pub use progress::{progress, Progress, Report};
pub use table::{num, reading, Csv};
