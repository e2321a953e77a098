//! The user's mistakes: [`BadInput`] (exit status 2) and how a library error is told in the
//! flags the user typed. Every layer may use this module; it uses none of them.

use anyhow::Result;

/// Bad input from the user: exit status 2.
#[derive(Debug)]
pub struct BadInput(pub String);

impl std::fmt::Display for BadInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BadInput {}

/// Return a [`BadInput`] error.
pub fn bad<T>(msg: impl Into<String>) -> Result<T> {
    Err(BadInput(msg.into()).into())
}

/// Whether an error chain is the user's fault (bad parameter, unknown name, undefined quantity).
pub fn is_bad_input(err: &anyhow::Error) -> bool {
    err.chain().any(|e| {
        e.downcast_ref::<BadInput>().is_some()
            || matches!(
                e.downcast_ref::<trirhythm::Error>(),
                Some(
                    trirhythm::Error::InvalidParameter { .. }
                        | trirhythm::Error::Unknown { .. }
                        | trirhythm::Error::Undefined { .. }
                )
            )
    })
}
