//! Files written whole or not at all, for every crate that writes outputs (images, reports,
//! Verilog, VCDs, dumps).
//!
//! A file is written under a temporary name beside its destination ([`temp_beside`]: hidden,
//! `.shadecore-tmp-<pid>-<n>-<name>`) and renamed into place only when every byte is written
//! and flushed; on an error (a full disk, a file-size limit) the temporary file is removed and
//! the destination keeps what it had. A process killed mid-write leaves only a hidden
//! temporary file, never a truncated output under its real name ([`remove_stale_temps`] clears
//! those of a folder its writer owns).
//!
//! A destination that exists and is not a regular file (`/dev/null`, `/dev/stdout`, a named
//! pipe, `/dev/full`) is written directly: a rename would replace the device or pipe itself.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// The prefix of every temporary file name.
pub const TEMP_PREFIX: &str = ".shadecore-tmp-";

/// Whether `dest` exists and is not a regular file (a device or a pipe): written directly.
fn is_special(dest: &Path) -> bool {
    std::fs::metadata(dest).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// A fresh temporary name in `dest`'s folder (so the rename stays on one file system).
pub fn temp_beside(dest: &Path) -> PathBuf {
    static N: AtomicU64 = AtomicU64::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    let name = dest
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let dir = match dest.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    dir.join(format!("{TEMP_PREFIX}{}-{n}-{name}", std::process::id()))
}

/// A file being written under a temporary name; [`WholeFile::commit`] renames it into place,
/// dropping it uncommitted removes it.
pub struct WholeFile {
    file: Option<std::io::BufWriter<std::fs::File>>,
    /// `None`: `dest` is a device or pipe, written directly.
    temp: Option<PathBuf>,
    dest: PathBuf,
}

impl WholeFile {
    /// Start writing `dest` (its folder must exist). The error names `dest`.
    pub fn create(dest: &Path) -> Result<WholeFile, String> {
        let temp = (!is_special(dest)).then(|| temp_beside(dest));
        let file = std::fs::File::create(temp.as_deref().unwrap_or(dest))
            .map_err(|e| format!("cannot write {}: {e}", dest.display()))?;
        Ok(WholeFile {
            file: Some(std::io::BufWriter::new(file)),
            temp,
            dest: dest.to_path_buf(),
        })
    }

    /// Flush, then rename into place. The error names the destination; the temporary file is
    /// gone either way.
    pub fn commit(mut self) -> Result<(), String> {
        let fail = |e: std::io::Error| format!("cannot write {}: {e}", self.dest.display());
        let file = self.file.take().expect("committed once");
        let file = file.into_inner().map_err(|e| fail(e.into_error()))?;
        // The rename publishes the file: its bytes must have reached the file system (a write
        // error of a full disk can show only here, e.g. on network file systems).
        let Some(temp) = self.temp.take() else {
            return Ok(());
        };
        let synced = file.sync_data().or_else(ignore_unsupported).map_err(fail);
        drop(file);
        let renamed = synced.and_then(|()| std::fs::rename(&temp, &self.dest).map_err(fail));
        if renamed.is_err() {
            let _ = std::fs::remove_file(&temp);
        }
        renamed
    }
}

/// `sync_data` on a file that cannot be synced (a pipe, some special file systems) is no
/// error for our purpose.
fn ignore_unsupported(e: std::io::Error) -> std::io::Result<()> {
    match e.kind() {
        std::io::ErrorKind::Unsupported | std::io::ErrorKind::InvalidInput => Ok(()),
        _ => Err(e),
    }
}

impl Write for WholeFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.file.as_mut().expect("not committed").write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.file.as_mut().expect("not committed").flush()
    }
}

impl Drop for WholeFile {
    fn drop(&mut self) {
        if let (Some(_), Some(temp)) = (self.file.take(), &self.temp) {
            let _ = std::fs::remove_file(temp);
        }
    }
}

/// Write `bytes` to `dest` whole or not at all. The error is one line naming `dest`.
pub fn write_whole(dest: &Path, bytes: &[u8]) -> Result<(), String> {
    let mut f = WholeFile::create(dest)?;
    f.write_all(bytes)
        .map_err(|e| format!("cannot write {}: {e}", dest.display()))?;
    f.commit()
}

/// Run `write` on a fresh temporary name beside `dest` (it creates and fills that file), then
/// rename the file into place; on an error (`write`'s or the rename's, named after `dest`) the
/// temporary file is removed. For writers that need the file itself, e.g. a VCD behind a
/// simulator.
pub fn write_through<T>(
    dest: &Path,
    write: impl FnOnce(&Path) -> Result<T, String>,
) -> Result<T, String> {
    if is_special(dest) {
        return write(dest);
    }
    let temp = temp_beside(dest);
    let result = write(&temp).and_then(|t| {
        std::fs::rename(&temp, dest)
            .map(|()| t)
            .map_err(|e| format!("cannot write {}: {e}", dest.display()))
    });
    if result.is_err() {
        let _ = std::fs::remove_file(&temp);
    }
    result
}

/// Remove the temporary files [`WholeFile`] left in `dir` (a process killed mid-write). Call it
/// only for a folder the caller owns (e.g. under a lock): another process's file being written
/// would go too.
pub fn remove_stale_temps(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        if e.file_name().to_string_lossy().starts_with(TEMP_PREFIX) {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("shadecore-files-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn names(d: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_committed_file_replaces_the_old_one_and_leaves_no_temporary() {
        let d = scratch("commit");
        let p = d.join("a.txt");
        std::fs::write(&p, "old").unwrap();
        let mut f = WholeFile::create(&p).unwrap();
        f.write_all(b"new").unwrap();
        // Until the commit, the destination holds the old bytes.
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "old");
        f.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "new");
        assert_eq!(names(&d), ["a.txt"]);
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn an_uncommitted_file_leaves_the_old_one_and_no_temporary() {
        let d = scratch("drop");
        let p = d.join("a.txt");
        std::fs::write(&p, "old").unwrap();
        let mut f = WholeFile::create(&p).unwrap();
        f.write_all(b"half").unwrap();
        drop(f);
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "old");
        assert_eq!(names(&d), ["a.txt"]);
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// A device is written directly, never replaced by a rename; its write error is the
    /// error.
    #[test]
    fn devices_are_written_directly() {
        write_whole(Path::new("/dev/null"), b"x").unwrap();
        assert!(!std::fs::metadata("/dev/null").unwrap().is_file());
        if Path::new("/dev/full").exists() {
            let e = write_whole(Path::new("/dev/full"), &[0; 1 << 16]).unwrap_err();
            assert!(e.contains("/dev/full") && !e.contains('\n'), "{e}");
            assert!(!std::fs::metadata("/dev/full").unwrap().is_file());
            let e = write_through(Path::new("/dev/full"), |p| {
                std::fs::write(p, [0; 1 << 16]).map_err(|e| e.to_string())
            })
            .unwrap_err();
            assert!(e.contains("No space"), "{e}");
        }
    }

    #[test]
    fn errors_name_the_destination_and_stale_temporaries_are_removed() {
        let d = scratch("errors");
        let e = write_whole(&d.join("no/such/dir/a.txt"), b"x").unwrap_err();
        assert!(e.contains("no/such/dir/a.txt") && !e.contains('\n'), "{e}");
        std::fs::write(temp_beside(&d.join("b.png")), "left by a kill").unwrap();
        std::fs::write(d.join("keep.txt"), "mine").unwrap();
        remove_stale_temps(&d);
        assert_eq!(names(&d), ["keep.txt"]);
        std::fs::remove_dir_all(&d).unwrap();
    }
}
