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
                        | trirhythm::Error::Malformed { .. }
                        | trirhythm::Error::NotApplicable { .. }
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
    ("noises", "--noises"),
    ("d_range", "--d-range"),
    ("points", "--points"),
    ("sweep", "--sweep"),
    ("bins", "--bins"),
    ("joint_bins", "--joint-bins"),
    ("amplitude_max", "--amplitude-max"),
    ("sample_every", "--sample-every"),
    ("record_every", "--every"),
    ("every", "--every"),
    ("max_step", "--step"),
    ("clones", "--clones"),
    ("max_excursion", "--max-excursion"),
    ("max_iterations", "--max-iterations"),
    ("core_quantile", "--core-quantile"),
    ("batches", "--batches"),
    ("z", "--z"),
    ("z_lenient", "--z-lenient"),
    ("z_strict", "--z-strict"),
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

/// The allowed range of every whole-number flag, per command (`*`: every command that has the
/// flag), as the command's own check states it: clap refuses `--every -1` or `--paths 1e3`
/// before that check runs, and its message ("invalid digit found in string") gives no range.
pub const WHOLE_NUMBER_FLAGS: &[(&str, &str, &str)] = &[
    ("ensemble", "--paths", "1 to 1000000"),
    ("map", "--paths", "1 to 1000000"),
    ("map", "--batches", "4 to 1000"),
    ("lyapunov", "--paths", "1 to 100000"),
    ("critical-noise", "--paths", "1 to 100000"),
    ("*", "--seed", "0 to 18446744073709551615"),
    ("*", "--every", "1 or more"),
    ("*", "--sample-every", "1 or more"),
    ("*", "--bins", "2 to 10000"),
    ("*", "--joint-bins", "2 to 1000"),
    ("*", "--renormalise-every", "1 to 1000000 steps"),
    ("critical-noise", "--points", "2 to 1000"),
    ("*", "--lanes", "1, 4 or 8"),
    ("ensemble", "--clones", "4 to 100000"),
    ("ensemble", "--max-iterations", "1 or more"),
    (
        "phase-response",
        "--phases",
        "an even number from 8 to 4096",
    ),
    ("phase-response", "--periods", "6 to 100000"),
];

/// The allowed range of whole-number flag `flag` of `command`, if it is one.
pub fn whole_number_range(command: &str, flag: &str) -> Option<&'static str> {
    WHOLE_NUMBER_FLAGS
        .iter()
        .find(|(c, f, _)| *f == flag && *c == command)
        .or_else(|| {
            WHOLE_NUMBER_FLAGS
                .iter()
                .find(|(c, f, _)| *f == flag && *c == "*")
        })
        .map(|(_, _, range)| *range)
}

/// clap's refusal of a value told like every other bad input: `--every = -1: allowed range is
/// 1 or more (a whole number)`, for the whole-number flags; `None` for any other error.
pub fn clap_value_error(command: &str, e: &clap::Error) -> Option<String> {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if !matches!(
        e.kind(),
        ErrorKind::InvalidValue | ErrorKind::ValueValidation
    ) {
        return None;
    }
    let text = |kind| match e.get(kind) {
        Some(ContextValue::String(s)) => Some(s.clone()),
        _ => None,
    };
    let arg = text(ContextKind::InvalidArg)?;
    let value = text(ContextKind::InvalidValue)?;
    let flag = arg.split([' ', '=']).next()?;
    let range = whole_number_range(command, flag)?;
    Some(format!(
        "{flag} = {value}: allowed range is {range} (a whole number)"
    ))
}
