//! Where output goes, and the promises kept on the way: a file appears whole or not at all.
//!
//! - Every file is written to a hidden temporary sibling (`.NAME.partial-PID.EXT`) and renamed
//!   into place when complete. The temporary is removed when the write fails (disk full, a
//!   closed device), when the command fails after creating it (the value is dropped
//!   uncommitted), and on SIGINT, SIGTERM or SIGHUP ([`install_signal_cleanup`]).
//! - Creating, committing and the signal cleanup take one lock, so a signal never races a
//!   temporary into existence after the cleanup: the cleanup holds the lock until the process
//!   has exited.
//! - A destination that is a directory, an existing non-regular file (a device, a pipe), or
//!   whose directory does not exist, is bad input, refused before any work starts
//!   ([`check_destination`]).
//! - A destination directory (`--out-dir`, `--checkpoint`) is checked the same way: it, or
//!   the nearest existing directory above it, must take a new file ([`check_dir_writable`]).
//! - A temporary left by a killed run (SIGKILL, a crash: `.NAME.partial-PID…`) is removed by
//!   the next run on the same destination, when process PID no longer runs
//!   ([`remove_stale_temporaries`]; on systems without `/proc` it is left alone).
//! - A directory is replaced only when everything in it is this tool's own
//!   ([`TemporaryDir::commit_replacing`]): checked before the replacement, and again after the
//!   previous one is moved aside; its files are then removed by name, never with everything
//!   in it, and a file that cannot be removed is an error naming the path.
//! - A directory claimed by a run ([`DirLock`], `dir/lock` created with `create_new`) is
//!   released like a temporary: when dropped and on SIGINT, SIGTERM or SIGHUP.
//! - Standard output: a closed pipe ends the command quietly (exit 0); any other write error
//!   (a full device) is an error (exit 1). `main` flushes standard output itself so that the
//!   error is seen.
//!
//! Tests: `tests/hostile.rs` (output onto a directory, into a missing directory, onto
//! /dev/full, SIGINT and SIGTERM during long runs leave no temporary; a report never deletes a
//! file it did not write, unwritable destinations, stale temporaries of killed runs).

use crate::error::bad;
use anyhow::{Context, Result};
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The temporaries that exist now.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// On SIGINT, SIGTERM or SIGHUP: remove every temporary and exit with 130.
pub fn install_signal_cleanup() {
    // failure to install (a handler already set) leaves the default behaviour: no cleanup, but
    // no other harm either
    let _ = ctrlc::set_handler(|| {
        // keep the lock until exit: no temporary can be created or renamed after this
        let list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
        for p in list.iter() {
            remove(p);
        }
        eprintln!("interrupted: no output written");
        std::process::exit(130);
    });
}

/// Remove a temporary: a file, or a directory being built with everything in it.
fn remove(path: &Path) {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_dir() => {
            let _ = std::fs::remove_dir_all(path);
        }
        Ok(_) => {
            let _ = std::fs::remove_file(path);
        }
        Err(_) => {}
    }
}

/// Refuse a destination that cannot receive a file: a directory, or a path in a directory that
/// does not exist. Call before any work starts.
pub fn check_destination(path: &Path, flag: &str) -> Result<()> {
    if path.as_os_str().is_empty() {
        return bad(format!("{flag}: the file name is empty"));
    }
    if path.is_dir() {
        return bad(format!(
            "{flag} {}: is a directory; give a file name",
            path.display()
        ));
    }
    if path.file_name().is_none() {
        return bad(format!("{flag} {}: not a file name", path.display()));
    }
    // a device, pipe or socket would be replaced by the rename: refuse it (standard output is
    // the way to write to a pipe)
    if let Ok(meta) = std::fs::metadata(path) {
        if !meta.is_file() {
            return bad(format!(
                "{flag} {}: exists and is not a regular file; give a file name, or leave {flag} \
                 out to write to standard output",
                path.display()
            ));
        }
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !parent.is_dir() {
        return bad(format!(
            "{flag} {}: directory {} does not exist",
            path.display(),
            parent.display()
        ));
    }
    Ok(())
}

/// [`check_destination`], and that its directory takes a new file: a probe file (a hidden
/// sibling) is created and removed at once. Call before any long work, so that a read-only
/// destination is refused before the computation rather than after it.
pub fn check_writable(path: &Path, flag: &str) -> Result<()> {
    check_destination(path, flag)?;
    let probe = temporary_sibling(path);
    match OpenOptions::new().write(true).create_new(true).open(&probe) {
        Ok(f) => {
            drop(f);
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        Err(e) => bad(format!(
            "{flag} {}: cannot write in its directory ({e})",
            path.display()
        )),
    }
}

/// Create and remove a hidden probe file in `dir`: whether `dir` takes a new file.
pub fn probe_dir(dir: &Path) -> std::io::Result<()> {
    let probe = dir.join(format!(".trirhythm-probe-{}", std::process::id()));
    let f = OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)?;
    drop(f);
    std::fs::remove_file(&probe)
}

/// Refuse a destination directory that cannot be written, before any work: `dir` itself when
/// it exists (it must be a directory), else the nearest existing directory above it (where it
/// would be created). Bad input naming `flag`.
pub fn check_dir_writable(dir: &Path, flag: &str) -> Result<()> {
    let shown = dir.display();
    if dir.as_os_str().is_empty() {
        return bad(format!("{flag}: the directory name is empty"));
    }
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => {
            return probe_dir(dir)
                .or_else(|e| bad(format!("{flag} {shown}: cannot write in it ({e})")))
        }
        Ok(_) => {
            return bad(format!(
                "{flag} {shown}: exists and is not a directory; give a directory"
            ))
        }
        Err(_) => {}
    }
    // the nearest existing ancestor, where the directory would be created
    let mut up = dir.parent();
    while let Some(p) = up {
        let p = if p.as_os_str().is_empty() {
            Path::new(".")
        } else {
            p
        };
        match std::fs::metadata(p) {
            Ok(m) if m.is_dir() => {
                return probe_dir(p).or_else(|e| {
                    bad(format!(
                        "{flag} {shown}: cannot be created, {} takes no new file ({e})",
                        p.display()
                    ))
                })
            }
            Ok(_) => {
                return bad(format!(
                    "{flag} {shown}: cannot be created, {} is not a directory",
                    p.display()
                ))
            }
            Err(_) => up = p.parent(),
        }
    }
    bad(format!("{flag} {shown}: cannot be created"))
}

/// Whether process `pid` may still run: on a system with `/proc`, whether `/proc/PID` exists;
/// elsewhere always (nothing is removed on a guess).
fn may_run(pid: u32) -> bool {
    !Path::new("/proc/self").exists() || Path::new(&format!("/proc/{pid}")).exists()
}

/// Remove the temporaries of `target` that killed runs left (`.NAME.partial-PID` and
/// `.NAME.partial-PID.EXT`, files or directories being built), when process PID no longer
/// runs (this process's own id counts as stale: it is about to be made afresh). A temporary
/// that cannot be removed is named in a warning; one whose process runs is left alone.
pub fn remove_stale_temporaries(target: &Path) {
    let Some(name) = target.file_name().map(|n| n.to_string_lossy().into_owned()) else {
        return;
    };
    let ext = target
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    let parent = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    let prefix = format!(".{name}.partial-");
    for e in entries.flatten() {
        let entry = e.file_name().to_string_lossy().into_owned();
        let Some(rest) = entry.strip_prefix(&prefix) else {
            continue;
        };
        let digits: String = rest.chars().take_while(|c| c.is_ascii_digit()).collect();
        let tail = &rest[digits.len()..];
        let Ok(pid) = digits.parse::<u32>() else {
            continue;
        };
        if !(tail.is_empty() || tail == ext) {
            continue;
        }
        if pid != std::process::id() && may_run(pid) {
            continue;
        }
        let path = e.path();
        let removed = match std::fs::symlink_metadata(&path) {
            Ok(m) if m.is_dir() => std::fs::remove_dir_all(&path),
            Ok(_) => std::fs::remove_file(&path),
            Err(_) => Ok(()),
        };
        if let Err(err) = removed {
            crate::io::progress::note(&format!(
                "warning: {} was left by a killed run (process {pid}) and could not be \
                 removed ({err}); remove it by hand",
                path.display()
            ));
        }
    }
}

/// `dir/.name.partial-PID.ext`: a hidden sibling keeping the extension (image encoders pick the
/// format from it).
fn temporary_sibling(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let ext = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.partial-{}{ext}", std::process::id()))
}

/// A file being written: a registered temporary that becomes `target` on [`Temporary::commit`]
/// and is removed if dropped before.
pub struct Temporary {
    path: PathBuf,
    target: PathBuf,
    committed: bool,
}

impl Temporary {
    /// Register and create the temporary of `target`, returning it with a buffered writer.
    pub fn create(target: &Path) -> Result<(Temporary, BufWriter<File>)> {
        check_destination(target, "output")?;
        remove_stale_temporaries(target);
        let path = temporary_sibling(target);
        let mut list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
        list.push(path.clone());
        let file = File::create(&path);
        drop(list);
        let tmp = Temporary {
            path,
            target: target.to_path_buf(),
            committed: false,
        };
        let file = file.with_context(|| format!("creating {}", tmp.path.display()))?;
        Ok((tmp, BufWriter::with_capacity(1 << 16, file)))
    }

    /// The temporary's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Rename the complete temporary onto its target.
    pub fn commit(mut self) -> Result<()> {
        let mut list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
        let renamed = std::fs::rename(&self.path, &self.target)
            .with_context(|| format!("renaming to {}", self.target.display()));
        list.retain(|p| p != &self.path);
        drop(list);
        if renamed.is_ok() {
            self.committed = true;
        }
        renamed
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if !self.committed {
            let mut list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
            let _ = std::fs::remove_file(&self.path);
            list.retain(|p| p != &self.path);
        }
    }
}

/// A directory being built: a registered hidden sibling `.NAME.partial-PID` of its target,
/// removed with everything in it when dropped uncommitted and on SIGINT, SIGTERM or SIGHUP, and
/// renamed onto the target when complete ([`TemporaryDir::commit_replacing`]).
pub struct TemporaryDir {
    path: PathBuf,
    target: PathBuf,
    committed: bool,
}

/// What a directory holds when all of it is this tool's own output: the paths relative to it,
/// files before the directories that hold them (the order they are removed in), or the first
/// entry that is not its own, in words.
pub type OwnEntries = std::result::Result<Vec<PathBuf>, String>;

impl TemporaryDir {
    /// Create the temporary directory of `target` (whose parent must exist), removing the
    /// temporaries of killed runs on the same target first.
    pub fn create(target: &Path) -> Result<TemporaryDir> {
        remove_stale_temporaries(target);
        let path = temporary_sibling(target);
        let mut list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
        list.push(path.clone());
        let made = std::fs::create_dir(&path);
        drop(list);
        let tmp = TemporaryDir {
            path,
            target: target.to_path_buf(),
            committed: false,
        };
        made.with_context(|| format!("creating {}", tmp.path.display()))?;
        Ok(tmp)
    }

    /// The temporary directory.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Rename the complete directory onto its target, which is checked again now (it may have
    /// changed while the directory was built): absent or empty, it is taken; a directory whose
    /// every entry `own` recognises (a previous output of the same kind) is replaced. Anything
    /// else — a file, a directory holding one entry `own` does not know — is bad input naming
    /// `flag`, and the target is left as it was (the new directory is dropped). Replacing
    /// moves the previous directory aside, checks it again there (an entry added in between
    /// puts it back and refuses), renames the new one into place and removes the previous
    /// one's entries by name; an entry that cannot be removed is an error naming the path.
    /// The cleanup's lock is held throughout: a signal waits for the renames.
    pub fn commit_replacing(mut self, flag: &str, own: &dyn Fn(&Path) -> OwnEntries) -> Result<()> {
        let list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
        let shown = self.target.display().to_string();
        let refuse = |why: String| -> Result<()> {
            bad(format!(
                "{flag} {shown}: {why}, which this run did not write (it appeared while the \
                 run worked); nothing was replaced and the new output was not kept"
            ))
        };
        let outcome = (|| -> Result<()> {
            match std::fs::symlink_metadata(&self.target) {
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                    // a directory made meanwhile makes the rename fail unless it is empty
                    return match std::fs::rename(&self.path, &self.target) {
                        Ok(()) => Ok(()),
                        Err(_) if self.target.exists() => self.replace(&refuse, own),
                        Err(e) => Err(e).with_context(|| format!("renaming to {shown}")),
                    };
                }
                Err(e) => return Err(e).with_context(|| format!("reading {shown}")),
                Ok(m) if !m.is_dir() => {
                    return refuse("it is now a file or a link".into());
                }
                Ok(_) => {}
            }
            self.replace(&refuse, own)
        })();
        let mut list = list;
        list.retain(|p| p != &self.path);
        drop(list);
        if outcome.is_ok() {
            self.committed = true;
        }
        outcome
    }

    /// [`TemporaryDir::commit_replacing`] onto an existing directory (the lock held).
    fn replace(
        &self,
        refuse: &dyn Fn(String) -> Result<()>,
        own: &dyn Fn(&Path) -> OwnEntries,
    ) -> Result<()> {
        let shown = self.target.display().to_string();
        if !std::fs::symlink_metadata(&self.target).is_ok_and(|m| m.is_dir()) {
            return refuse("it is now a file or a link".into());
        }
        let entries = match own(&self.target) {
            Ok(e) => e,
            Err(foreign) => return refuse(format!("it holds {foreign}")),
        };
        if entries.is_empty() {
            // an empty directory: replaced by the rename itself (it fails if a file appeared)
            return match std::fs::rename(&self.path, &self.target) {
                Ok(()) => Ok(()),
                Err(_) => match own(&self.target) {
                    Err(foreign) => refuse(format!("it holds {foreign}")),
                    Ok(_) => Err(anyhow::anyhow!(
                        "renaming to {shown}: the directory changed"
                    )),
                },
            };
        }
        let name = self
            .target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let aside = self
            .target
            .with_file_name(format!(".{name}.replaced-{}", std::process::id()));
        if aside.exists() {
            return Err(anyhow::anyhow!(
                "{} exists (a previous run of this process id); remove it by hand",
                aside.display()
            ));
        }
        std::fs::rename(&self.target, &aside)
            .with_context(|| format!("moving the previous {shown} aside"))?;
        let put_back = || {
            if !self.target.exists() {
                let _ = std::fs::rename(&aside, &self.target);
            }
        };
        // checked again where it now is: an entry added between the check and the move
        let entries = match own(&aside) {
            Ok(e) => e,
            Err(foreign) => {
                put_back();
                return refuse(format!("it holds {foreign}"));
            }
        };
        if let Err(e) = std::fs::rename(&self.path, &self.target) {
            put_back();
            return Err(e).with_context(|| format!("renaming to {shown}"));
        }
        // the previous entries, by name: what is not its own stays (and is named)
        for rel in &entries {
            let p = aside.join(rel);
            let removed = match std::fs::symlink_metadata(&p) {
                Ok(m) if m.is_dir() => std::fs::remove_dir(&p),
                Ok(_) => std::fs::remove_file(&p),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
                Err(e) => Err(e),
            };
            removed.with_context(|| {
                format!(
                    "the new {shown} is in place, but the previous one, moved to {}, could not \
                     be removed: {}; remove {} by hand",
                    aside.display(),
                    p.display(),
                    aside.display()
                )
            })?;
        }
        std::fs::remove_dir(&aside).with_context(|| {
            let left: Vec<String> = std::fs::read_dir(&aside)
                .map(|d| {
                    d.flatten()
                        .map(|e| e.file_name().to_string_lossy().into_owned())
                        .collect()
                })
                .unwrap_or_default();
            format!(
                "the new {shown} is in place, but the previous one, moved to {}, could not be \
                 removed (it holds {}, which this run did not write and left alone); remove \
                 it by hand",
                aside.display(),
                if left.is_empty() {
                    "nothing".to_string()
                } else {
                    left.join(", ")
                }
            )
        })
    }
}

impl Drop for TemporaryDir {
    fn drop(&mut self) {
        if !self.committed {
            let mut list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
            remove(&self.path);
            list.retain(|p| p != &self.path);
        }
    }
}

/// Read and validate a model file named by `flag` (a file that cannot be read is bad input).
pub fn read_model(path: &Path, flag: &str) -> Result<trirhythm::model::Model> {
    let text = match std::fs::read_to_string(path) {
        Ok(text) => text,
        Err(e) => return bad(format!("{flag} {}: cannot read it: {e}", path.display())),
    };
    trirhythm::model::Model::from_toml_str(&text)
        .with_context(|| format!("{flag} {}", path.display()))
}

/// Write a whole file atomically: complete under its name, or nothing.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let (tmp, mut w) = Temporary::create(path)?;
    w.write_all(bytes)
        .and_then(|()| w.flush())
        .with_context(|| format!("writing {}", tmp.path().display()))?;
    drop(w);
    tmp.commit()
}

/// Write `bytes` to standard output (buffered; `main` flushes).
pub fn stdout_write(bytes: &[u8]) -> Result<()> {
    std::io::stdout()
        .lock()
        .write_all(bytes)
        .context("writing to standard output")
}

/// Whether an error chain is a closed pipe on the other end of standard output.
pub fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|e| {
        e.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

/// A destination opened for streaming: standard output or an atomic file.
pub enum Stream {
    /// Standard output (buffered).
    Stdout(BufWriter<std::io::Stdout>),
    /// A temporary to be committed.
    File(Temporary, BufWriter<File>),
}

impl Stream {
    /// Open `out` (a file) or standard output.
    pub fn open(out: Option<&Path>) -> Result<Stream> {
        Ok(match out {
            Some(p) => {
                let (t, w) = Temporary::create(p)?;
                Stream::File(t, w)
            }
            None => Stream::Stdout(BufWriter::with_capacity(1 << 16, std::io::stdout())),
        })
    }

    /// The writer.
    pub fn writer(&mut self) -> &mut dyn Write {
        match self {
            Stream::Stdout(w) => w,
            Stream::File(_, w) => w,
        }
    }

    /// Flush and, for a file, rename it into place.
    pub fn finish(self) -> Result<()> {
        match self {
            Stream::Stdout(mut w) => w.flush().context("writing to standard output"),
            Stream::File(t, mut w) => {
                w.flush()
                    .with_context(|| format!("writing {}", t.path().display()))?;
                drop(w);
                t.commit()
            }
        }
    }
}

/// An exclusive claim on a directory (`dir/lock`, created with `create_new`, holding the
/// process id and what the run is): removed when dropped and, like a temporary, on SIGINT,
/// SIGTERM or SIGHUP. A lock left by a killed run (SIGKILL, a crash) stays and is removed by
/// hand; the refusal says so, and on Linux says whether its process still runs.
pub struct DirLock {
    path: PathBuf,
}

impl DirLock {
    /// Claim `dir` for a run described by `what`; refused (bad input) while another holds it.
    pub fn claim(dir: &Path, what: &str) -> Result<DirLock> {
        let path = dir.join("lock");
        // registered under the cleanup's lock before it exists: a signal never leaves it behind
        let mut list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
        let created = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path);
        match created {
            Ok(mut f) => {
                list.push(path.clone());
                drop(list);
                let lock = DirLock { path };
                f.write_all(format!("pid {}\n{what}", std::process::id()).as_bytes())
                    .and_then(|()| f.flush())
                    .with_context(|| format!("writing {}", lock.path.display()))?;
                Ok(lock)
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                drop(list);
                let owner = std::fs::read_to_string(&path).ok().and_then(|t| {
                    t.lines()
                        .next()
                        .and_then(|l| l.strip_prefix("pid "))
                        .and_then(|p| p.trim().parse::<u32>().ok())
                });
                let who = match owner {
                    Some(pid) => {
                        let gone = Path::new("/proc/self").exists()
                            && !Path::new(&format!("/proc/{pid}")).exists();
                        if gone {
                            format!(
                                "process {pid}, which no longer runs (a killed run left the \
                                 lock)"
                            )
                        } else {
                            format!("process {pid}")
                        }
                    }
                    None => "an unknown process".to_string(),
                };
                bad(format!(
                    "--checkpoint {}: in use by {who}; wait for it to finish, or if no run \
                     owns it any more, remove {} by hand",
                    dir.display(),
                    path.display()
                ))
            }
            Err(e) => {
                drop(list);
                Err(e).with_context(|| format!("creating {}", path.display()))
            }
        }
    }
}

impl Drop for DirLock {
    fn drop(&mut self) {
        let mut list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
        let _ = std::fs::remove_file(&self.path);
        list.retain(|p| p != &self.path);
    }
}
