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
//! - A directory claimed by a run ([`DirLock`], `dir/lock` created with `create_new`) is
//!   released like a temporary: when dropped and on SIGINT, SIGTERM or SIGHUP.
//! - Standard output: a closed pipe ends the command quietly (exit 0); any other write error
//!   (a full device) is an error (exit 1). `main` flushes standard output itself so that the
//!   error is seen.
//!
//! Tests: `tests/hostile.rs` (output onto a directory, into a missing directory, onto
//! /dev/full, SIGINT and SIGTERM during long runs leave no temporary).

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
    /// Register the temporary of `target` (without creating it: encoders that write by path
    /// create it themselves).
    pub fn reserve(target: &Path) -> Result<Temporary> {
        check_destination(target, "output")?;
        let path = temporary_sibling(target);
        TEMPORARIES
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(path.clone());
        Ok(Temporary {
            path,
            target: target.to_path_buf(),
            committed: false,
        })
    }

    /// Register and create the temporary of `target`, returning it with a buffered writer.
    pub fn create(target: &Path) -> Result<(Temporary, BufWriter<File>)> {
        check_destination(target, "output")?;
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
/// renamed onto the target when complete ([`TemporaryDir::commit`]).
pub struct TemporaryDir {
    path: PathBuf,
    target: PathBuf,
    committed: bool,
}

impl TemporaryDir {
    /// Create the temporary directory of `target` (whose parent must exist).
    pub fn create(target: &Path) -> Result<TemporaryDir> {
        let path = temporary_sibling(target);
        let mut list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
        // a stale one of a killed run with the same process id: start afresh
        remove(&path);
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

    /// Rename the complete directory onto its target. A target that exists (the caller has
    /// decided that it may be replaced) is moved aside first and removed after; a signal during
    /// the renames waits for them and then removes what is left aside.
    pub fn commit(mut self) -> Result<()> {
        let mut list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
        let aside = self.target.exists().then(|| {
            let name = self
                .target
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            self.target
                .with_file_name(format!(".{name}.replaced-{}", std::process::id()))
        });
        let renamed = (|| -> Result<()> {
            if let Some(aside) = &aside {
                remove(aside);
                std::fs::rename(&self.target, aside).with_context(|| {
                    format!("moving the previous {} aside", self.target.display())
                })?;
                list.push(aside.clone());
            }
            std::fs::rename(&self.path, &self.target)
                .with_context(|| format!("renaming to {}", self.target.display()))
        })();
        if renamed.is_err() {
            // put the previous directory back
            if let Some(aside) = &aside {
                if !self.target.exists() {
                    let _ = std::fs::rename(aside, &self.target);
                }
            }
        }
        list.retain(|p| p != &self.path);
        if renamed.is_ok() {
            self.committed = true;
        }
        drop(list);
        if let Some(aside) = &aside {
            let mut list = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
            if renamed.is_ok() {
                remove(aside);
            }
            list.retain(|p| p != aside);
        }
        renamed
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
