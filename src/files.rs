//! The user's files, and the one layer every read and write goes through.
//!
//! - Inputs: a scene is read with a size limit and checked to be UTF-8 ([`read_scene`]); a
//!   file a scene names (a cam file) must lie under the scene's folder or a folder the user
//!   allowed, be a regular file, and is read without blocking ([`read_referenced`]). Every
//!   file read is remembered as one of the run's inputs.
//! - Outputs: an output is never one of the run's inputs (same device and inode, through
//!   links and `..`): [`refuse_inputs`]. It is written to a temporary file with a unique
//!   name beside it, created exclusively (`O_EXCL`, never through a link), and renamed over
//!   the old file only when complete ([`AtomicFile`], [`write_atomically`]); the temporary
//!   file is removed on an error, and on Ctrl-C or SIGTERM once
//!   [`remove_temporaries_on_signal`] is installed.

use std::fs::{self, File};
use std::io::{self, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

use tempfile::NamedTempFile;

use crate::error::{Error, Location, Result};
/// The largest scene file read (bytes): 16 MiB, room for a list of a million drive
/// positions written with 12 characters each.
pub const MAX_SCENE_BYTES: u64 = 16 << 20;

/// Reads a scene file's text: at most [`MAX_SCENE_BYTES`] (so `/dev/zero` or a wrong file
/// does not eat the memory), and UTF-8 (else the error gives the first invalid byte's
/// offset, line and column). The file becomes one of the run's inputs (see
/// [`refuse_inputs`]).
pub fn read_scene(path: &Path) -> Result<String> {
    read_input(path, "the scene file")
}

/// Reads an input file the user named on the command line as [`read_scene`] does; `role`
/// says what it is in messages (`"the imported file"`).
pub fn read_input(path: &Path, role: &'static str) -> Result<String> {
    let file = File::open(path).map_err(|source| Error::Read {
        path: path.to_owned(),
        source,
    })?;
    remember_input(&file, path, role);
    read_text(file, path)
}

/// Reads a file that the scene file `scene` names (`written` as in the scene: relative to
/// the scene's folder, e.g. `[drive] cam`), with the care a file the user did not name on
/// the command line needs:
///
/// - it must lie under the scene's folder, after resolving links and `..`, or under a
///   folder the user allowed ([`allow_folder`], the tool's `--allow-path`);
/// - it must be a regular file (a FIFO, a device, a folder or a file of `/proc`, `/sys` or
///   `/dev` is refused), checked before opening and again on the open handle, opened
///   without blocking;
/// - at most [`MAX_SCENE_BYTES`], UTF-8.
///
/// Returns the path (the scene's folder joined with `written`) and the text; the file
/// becomes one of the run's inputs, described by `role`.
///
/// # Errors
/// [`Error::OutsideSceneFolder`], [`Error::NotRegularFile`], and [`read_scene`]'s errors.
/// None quotes the file's content.
pub fn read_referenced(
    written: &str,
    scene: &Path,
    role: &'static str,
) -> Result<(PathBuf, String)> {
    let (folder, path) = match scene.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => (dir, dir.join(written)),
        _ => (Path::new("."), PathBuf::from(written)),
    };
    let read_error = |source| Error::Read {
        path: path.clone(),
        source,
    };
    let canonical = fs::canonicalize(&path).map_err(read_error)?;
    let folder_canonical = fs::canonicalize(folder).map_err(|source| Error::Read {
        path: folder.to_owned(),
        source,
    })?;
    let allowed = lock(&ALLOWED_FOLDERS).clone();
    if !canonical.starts_with(&folder_canonical)
        && !allowed.iter().any(|d| canonical.starts_with(d))
    {
        return Err(Error::OutsideSceneFolder {
            path,
            resolved: canonical,
            folder: folder_canonical,
        });
    }
    let not_regular = |kind: &'static str| Error::NotRegularFile {
        path: path.clone(),
        kind,
    };
    if VIRTUAL_FILE_SYSTEMS
        .iter()
        .any(|root| canonical.starts_with(root))
    {
        return Err(not_regular("a file of the kernel's /proc, /sys or /dev"));
    }
    let kind = fs::metadata(&canonical).map_err(read_error)?.file_type();
    if !kind.is_file() {
        return Err(not_regular(describe(kind)));
    }
    let mut options = File::options();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        // Swapped for a FIFO since the check, the open still returns at once.
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(&canonical).map_err(read_error)?;
    let kind = file.metadata().map_err(read_error)?.file_type();
    if !kind.is_file() {
        return Err(not_regular(describe(kind)));
    }
    remember_input(&file, &path, role);
    let text = read_text(file, &path)?;
    Ok((path, text))
}

/// Lets the scenes of this run name files under `folder` too (besides their own folder):
/// the tool's `--allow-path DIR`.
///
/// # Errors
/// [`Error::Read`] if `folder` does not exist.
pub fn allow_folder(folder: &Path) -> Result<()> {
    let canonical = fs::canonicalize(folder).map_err(|source| Error::Read {
        path: folder.to_owned(),
        source,
    })?;
    lock(&ALLOWED_FOLDERS).push(canonical);
    Ok(())
}

/// The roots of the kernel's virtual file systems: their "regular" files (`/proc/self/environ`)
/// are not files a scene names, even in an allowed folder.
const VIRTUAL_FILE_SYSTEMS: [&str; 3] = ["/proc", "/sys", "/dev"];

/// What a file that is not a regular file is, for the message.
fn describe(kind: fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if kind.is_char_device() || kind.is_block_device() {
            return "a device";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    if kind.is_dir() {
        "a folder"
    } else {
        "not a regular file"
    }
}

/// The text of `file`: at most [`MAX_SCENE_BYTES`], UTF-8; errors name `path`.
fn read_text(file: File, path: &Path) -> Result<String> {
    let mut bytes = Vec::new();
    file.take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|source| Error::Read {
            path: path.to_owned(),
            source,
        })?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(Error::TooLarge {
            path: path.to_owned(),
            limit: MAX_SCENE_BYTES,
        });
    }
    String::from_utf8(bytes).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        let bytes = e.as_bytes();
        let before = String::from_utf8_lossy(&bytes[..offset]);
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        Error::NotUtf8 {
            location: Location {
                file: path.display().to_string().into(),
                line: before.matches('\n').count() + 1,
                column: before[line_start..].chars().count() + 1,
            },
            offset,
            byte: bytes[offset],
        }
    })
}

/// A file on disk, whatever its name: device, inode and birth time (elsewhere, the
/// resolved path). The birth time tells a file that reuses the inode of a deleted input
/// (a process that reads and deletes many files: a study, the tests) from that input;
/// renames and hard links keep it. `None` where the file system records none.
#[derive(Debug, Clone, PartialEq, Eq)]
enum FileId {
    #[cfg(unix)]
    Inode(u64, u64, Option<std::time::SystemTime>),
    #[cfg(not(unix))]
    Path(PathBuf),
}

impl FileId {
    fn of(metadata: &fs::Metadata, _path: &Path) -> Option<FileId> {
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            Some(FileId::Inode(
                metadata.dev(),
                metadata.ino(),
                metadata.created().ok(),
            ))
        }
        #[cfg(not(unix))]
        {
            let _ = metadata;
            fs::canonicalize(_path).ok().map(FileId::Path)
        }
    }
}

/// One of the run's inputs: the file, the path it was read by, and what it is.
#[derive(Debug, Clone)]
struct Input {
    id: FileId,
    path: PathBuf,
    role: &'static str,
}

/// The files read so far by this process (scenes, cam files, imported files).
static INPUTS: Mutex<Vec<Input>> = Mutex::new(Vec::new());

/// The folders a scene may name files in besides its own ([`allow_folder`]), resolved.
static ALLOWED_FOLDERS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The temporary files being written, removed by the signal handler.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The lists above stay usable after a panic elsewhere (they are only pushed to and read).
fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(PoisonError::into_inner)
}

fn remember_input(file: &File, path: &Path, role: &'static str) {
    let Some(id) = file.metadata().ok().and_then(|m| FileId::of(&m, path)) else {
        return;
    };
    let mut inputs = lock(&INPUTS);
    if !inputs.iter().any(|i| i.id == id) {
        inputs.push(Input {
            id,
            path: path.to_owned(),
            role,
        });
    }
}

/// Refuses outputs that are one of the run's inputs: a file read by [`read_scene`],
/// [`read_input`] or [`read_referenced`] in this process, named through any path (the same
/// device and inode: links, `..` and hard links are seen through). Every writer of this
/// module calls it; a command writing several files calls it with all of them first, so
/// that nothing is written when one is refused.
///
/// # Errors
/// [`Error::OutputIsInput`] naming the output and the input.
pub fn refuse_inputs<'a>(outputs: impl IntoIterator<Item = &'a Path>) -> Result<()> {
    for output in outputs {
        let Some(id) = fs::metadata(output)
            .ok()
            .and_then(|m| FileId::of(&m, output))
        else {
            continue;
        };
        if let Some(input) = lock(&INPUTS).iter().find(|i| i.id == id) {
            return Err(Error::OutputIsInput {
                output: output.to_owned(),
                role: input.role,
                input: input.path.clone(),
            });
        }
    }
    Ok(())
}

/// Whether `a` and `b` name the same file on disk (through links, `..` or hard links).
/// A path that does not exist is no file's.
pub fn same_file(a: &Path, b: &Path) -> bool {
    let (Ok(ma), Ok(mb)) = (fs::metadata(a), fs::metadata(b)) else {
        return false;
    };
    matches!((FileId::of(&ma, a), FileId::of(&mb, b)), (Some(x), Some(y)) if x == y)
}

/// Creates the folder of a folder output (`--plot DIR`) and its parents if missing.
///
/// # Errors
/// [`Error::Write`] naming `dir`.
pub fn create_output_folder(dir: &Path) -> Result<()> {
    fs::create_dir_all(dir).map_err(|source| Error::Write {
        path: dir.to_owned(),
        source,
    })
}

/// Writes `path` whole or not at all: `write` fills a temporary file in the same directory,
/// which is flushed, synced and then renamed over `path`. If anything fails, the temporary
/// file is removed and `path` is left as it was.
///
/// # Errors
/// [`Error::OutputIsInput`] if `path` is one of the run's inputs; [`Error::Write`] with the
/// operating system's reason (or the one `write` returned).
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<()> {
    let mut file = AtomicFile::create(path)?;
    write(file.writer()).map_err(|source| file.error(source))?;
    file.commit()
}

/// An output file written whole or not at all, as it is streamed: the bytes go to a
/// temporary file beside `path` (a unique hidden name `.NAME.XXXXXX.tmp`, created
/// exclusively: a link planted at any name is never followed), renamed over `path` by
/// [`AtomicFile::commit`]. Dropped without a commit (an error, a panic), the temporary file
/// is removed and `path` is left as it was; on Ctrl-C or SIGTERM too, once
/// [`remove_temporaries_on_signal`] is installed.
#[derive(Debug)]
pub struct AtomicFile {
    path: PathBuf,
    temporary: PathBuf,
    out: Option<BufWriter<NamedTempFile>>,
}

impl AtomicFile {
    /// Creates the temporary file for `path`.
    ///
    /// # Errors
    /// [`Error::OutputIsInput`] if `path` is one of the run's inputs; [`Error::Write`]
    /// naming `path` if the temporary file cannot be created.
    pub fn create(path: &Path) -> Result<Self> {
        refuse_inputs([path])?;
        let dir = match path.parent() {
            Some(dir) if !dir.as_os_str().is_empty() => dir,
            _ => Path::new("."),
        };
        let name = path
            .file_name()
            .map_or_else(|| "output".into(), |n| n.to_string_lossy());
        let mut live = lock(&TEMPORARIES);
        let prefix = format!(".{name}.");
        let mut builder = tempfile::Builder::new();
        builder.prefix(&prefix).suffix(".tmp");
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            // As a file created by `File::create`: 0666 less the umask (not tempfile's 0600).
            builder.permissions(fs::Permissions::from_mode(0o666));
        }
        let file = builder.tempfile_in(dir).map_err(|source| Error::Write {
            path: path.to_owned(),
            source,
        })?;
        let temporary = file.path().to_owned();
        live.push(temporary.clone());
        Ok(Self {
            path: path.to_owned(),
            temporary,
            out: Some(BufWriter::with_capacity(1 << 16, file)),
        })
    }

    /// Where the bytes go until the commit.
    pub fn writer(&mut self) -> &mut (dyn Write + Send) {
        self.out.as_mut().expect("written after its commit")
    }

    /// The file the user asked for.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// An error writing this file, named as the user's path.
    pub fn error(&self, source: io::Error) -> Error {
        Error::Write {
            path: self.path.clone(),
            source,
        }
    }

    /// Flushes and syncs the temporary file and renames it over the user's path.
    ///
    /// # Errors
    /// [`Error::Write`] with the operating system's reason; the temporary file is removed.
    pub fn commit(mut self) -> Result<()> {
        let out = self.out.take().expect("committed once");
        let file = out.into_inner().map_err(|e| self.error(e.into_error()))?;
        file.as_file().sync_all().map_err(|e| self.error(e))?;
        // On failure the temporary file comes back in the error, and is removed as it drops.
        file.persist(&self.path).map_err(|e| self.error(e.error))?;
        Ok(())
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        // Not committed: the temporary file is removed as it drops.
        drop(self.out.take());
        lock(&TEMPORARIES).retain(|t| *t != self.temporary);
    }
}

/// Removes the temporary files being written, then ends the process with status 128 + the
/// signal (130 for Ctrl-C, 143 for SIGTERM, 129 for SIGHUP), when one of these signals
/// arrives: the user's old files stay as they were, and nothing half-written is left.
/// Installed once by the `mechdiff` tool (a thread waits for the signals).
///
/// # Errors
/// The operating system's, if the handler cannot be installed.
#[cfg(unix)]
pub fn remove_temporaries_on_signal() -> io::Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    std::thread::Builder::new()
        .name("remove-temporaries".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                // Held until the exit: no temporary file is created after this point.
                let live = lock(&TEMPORARIES);
                for path in live.iter() {
                    let _ = fs::remove_file(path);
                }
                std::process::exit(128 + signal);
            }
        })?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporary_files_are_hidden_unique_and_in_the_output_directory() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("run.csv");
        let (a, b) = (
            AtomicFile::create(&path).unwrap(),
            AtomicFile::create(&path).unwrap(),
        );
        assert_ne!(a.temporary, b.temporary);
        for t in [&a.temporary, &b.temporary] {
            assert_eq!(t.parent(), Some(dir.path()));
            let name = t.file_name().unwrap().to_string_lossy().into_owned();
            assert!(
                name.starts_with(".run.csv.") && name.ends_with(".tmp"),
                "{name}"
            );
            assert!(t.exists());
        }
        let temporaries = [a.temporary.clone(), b.temporary.clone()];
        drop((a, b));
        assert!(temporaries.iter().all(|t| !t.exists()));
        assert!(!lock(&TEMPORARIES).iter().any(|t| temporaries.contains(t)));
    }
}
