//! The commands: each parses its arguments ([`crate::args`]), builds the library's types,
//! calls the library with a progress-bar monitor ([`crate::io::progress`]) and writes the
//! result ([`crate::io`], [`crate::render`]). A command never imports another command.

pub mod ensemble;
pub mod figure;
pub mod lyapunov;
pub mod maps;
pub mod model;
pub mod oscillation;
pub mod phase;
pub mod report;
pub mod simulate;
pub mod theory;
