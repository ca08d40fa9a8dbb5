//! The user's files: a scene is read with a size limit and checked to be UTF-8; an output is
//! written to a temporary file beside it and renamed over the old one only when complete,
//! and never onto the scene it came from.

use std::fs::{self, File};
use std::io::{self, BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use crate::error::{Error, Location, Result};

/// The largest scene file read (bytes): 16 MiB, room for a list of a million drive
/// positions written with 12 characters each.
pub const MAX_SCENE_BYTES: u64 = 16 << 20;

/// Reads a scene file's text: at most [`MAX_SCENE_BYTES`] (so `/dev/zero` or a wrong file
/// does not eat the memory), and UTF-8 (else the error gives the first invalid byte's
/// offset, line and column).
pub fn read_scene(path: &Path) -> Result<String> {
    let read_error = |source| Error::Read {
        path: path.to_owned(),
        source,
    };
    let file = File::open(path).map_err(read_error)?;
    let mut bytes = Vec::new();
    file.take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(read_error)?;
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

/// Whether `a` and `b` name the same file on disk (through links, `..` or hard links).
/// A path that does not exist is no file's.
pub fn same_file(a: &Path, b: &Path) -> bool {
    let (Ok(ma), Ok(mb)) = (fs::metadata(a), fs::metadata(b)) else {
        return false;
    };
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if (ma.dev(), ma.ino()) == (mb.dev(), mb.ino()) {
            return true;
        }
    }
    let _ = (ma, mb);
    matches!((fs::canonicalize(a), fs::canonicalize(b)), (Ok(x), Ok(y)) if x == y)
}

/// Writes `path` whole or not at all: `write` fills a temporary file in the same directory,
/// which is flushed, synced and then renamed over `path`. If anything fails, the temporary
/// file is removed and `path` is left as it was.
///
/// # Errors
/// [`Error::Write`] with the operating system's reason (or the one `write` returned).
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<()> {
    let mut file = AtomicFile::create(path)?;
    write(file.writer()).map_err(|source| file.error(source))?;
    file.commit()
}

/// An output file written whole or not at all, as it is streamed: the bytes go to a
/// temporary file beside `path`, renamed over `path` by [`AtomicFile::commit`]. Dropped
/// without a commit (an error, a panic), the temporary file is removed and `path` is left
/// as it was. (A process killed outright leaves the hidden temporary file behind, and
/// `path` as it was.)
#[derive(Debug)]
pub struct AtomicFile {
    path: PathBuf,
    temporary: PathBuf,
    out: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Creates the temporary file for `path`.
    ///
    /// # Errors
    /// [`Error::Write`] naming `path` if the temporary file cannot be created.
    pub fn create(path: &Path) -> Result<Self> {
        let temporary = temporary_beside(path);
        let file = File::options()
            .write(true)
            .create(true)
            .truncate(true)
            .open(&temporary)
            .map_err(|source| Error::Write {
                path: path.to_owned(),
                source,
            })?;
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
        let result = (|| {
            let file = out.into_inner().map_err(io::IntoInnerError::into_error)?;
            file.sync_all()?;
            fs::rename(&self.temporary, &self.path)
        })();
        result.map_err(|source| self.error(source))
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        // Not committed, or the commit failed before or at the rename: nothing of it may stay.
        if self.out.take().is_some() || self.temporary.exists() {
            let _ = fs::remove_file(&self.temporary);
        }
    }
}

/// `dir/.name.tmp-<pid>`: in the same directory (so the rename stays on one file system),
/// hidden, and unique to this process.
fn temporary_beside(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy());
    let temporary = format!(".{name}.tmp-{}", std::process::id());
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.join(temporary),
        _ => PathBuf::from(temporary),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporary_files_stay_in_the_output_directory() {
        let t = temporary_beside(Path::new("out/run.csv"));
        assert_eq!(t.parent(), Some(Path::new("out")));
        assert!(
            t.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with(".run.csv.tmp-")
        );
        assert_eq!(
            temporary_beside(Path::new("run.csv")).parent(),
            Some(Path::new(""))
        );
    }
}
