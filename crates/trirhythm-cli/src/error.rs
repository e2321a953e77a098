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

/// Unless `ok`, a [`BadInput`] `FLAG = VALUE: allowed range is RANGE`.
pub fn allowed(ok: bool, flag: &str, value: impl std::fmt::Display, range: &str) -> Result<()> {
    if ok {
        return Ok(());
    }
    bad(format!("{flag} = {value}: allowed range is {range}"))
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

/// The flag a user typed for each argument the library names in its errors (parameter keys
/// such as `lambda` or `D` are typed as they are named, with `--param`).
const FLAGS: &[(&str, &str)] = &[
    ("dt", "--dt"),
    ("tolerance", "--tolerance"),
    ("u0", "--u0"),
    ("v0", "--v0"),
    ("t_end", "--t-end"),
    ("burn_in", "--burn-in"),
    ("transient", "--transient"),
    ("paths", "--paths"),
    ("separation", "--separation"),
    ("renormalise_every", "--renormalise-every"),
    ("d_lo", "--d-range"),
    ("d_hi", "--d-range"),
    ("grid", "--grid"),
    ("refinements", "--refinements"),
    ("z", "--z"),
    ("bins", "--bins"),
    ("joint_bins", "--joint-bins"),
    ("amplitude_max", "--amplitude-max"),
    ("sample_every", "--sample-every"),
    ("record_every", "--every"),
    ("max_step", "--step"),
];

/// A library error told in the flag the user typed: `--t-end: invalid parameter t_end = …`.
pub fn in_flags(err: anyhow::Error) -> anyhow::Error {
    let flag = err
        .chain()
        .find_map(|e| match e.downcast_ref::<trirhythm::Error>() {
            Some(trirhythm::Error::InvalidParameter { name, .. }) => FLAGS
                .iter()
                .find(|(library, _)| library == name)
                .map(|(_, flag)| *flag),
            _ => None,
        });
    match flag {
        Some(flag) => err.context(flag),
        None => err,
    }
}
