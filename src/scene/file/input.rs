//! Reading an input file whole, within a size limit.

use std::path::Path;

/// The largest scene, points or report JSON file read (256 MiB).
pub const MAX_TEXT_BYTES: u64 = 256 << 20;

/// The largest OBJ file read (1 GiB).
pub const MAX_OBJ_BYTES: u64 = 1 << 30;

/// Why an input file could not be read ([`read_input`]); displayed as
/// one line.
#[derive(Debug)]
#[non_exhaustive]
pub enum InputError {
    /// The path is a directory.
    Directory,
    /// The path is a device, FIFO or socket, not a regular file.
    NotRegular,
    /// The file is longer than the limit, or grew past it while being read.
    TooLarge {
        /// Its length (at least; `limit + 1` when it grew while read).
        bytes: u64,
        /// The limit.
        limit: u64,
    },
    /// The system could not open or read it.
    Io(std::io::Error),
}

impl_error!(InputError, |error, f| match error {
    InputError::Directory => write!(f, "not a regular file (a directory)"),
    InputError::NotRegular => {
        write!(f, "not a regular file (a device, FIFO or socket)")
    }
    InputError::TooLarge { bytes, limit } => {
        write!(f, "{bytes} bytes or more, over the limit of {limit} bytes")
    }
    InputError::Io(e) => write!(f, "cannot read: {e}"),
});

/// The bytes of the regular file at `path`, at most `limit` of them.
///
/// Devices (`/dev/zero`), FIFOs, sockets and directories are refused before
/// they are opened (opening a FIFO would block until a writer comes), and
/// a file longer than `limit` — or one that grows past it while being read
/// — is refused rather than read whole.
///
/// # Errors
/// [`InputError`]: what the path is instead of a regular file, its size
/// against the limit, or the I/O error.
pub fn read_input(path: &Path, limit: u64) -> Result<Vec<u8>, InputError> {
    let (file, len) = open_input(path, limit)?;
    read_all(file, limit, len)
}

/// The bytes of an opened input of `len` bytes (as its metadata says), at
/// most `limit` of them, in a buffer of that size (not one doubled as it
/// grows).
pub(super) fn read_all(file: std::fs::File, limit: u64, len: u64) -> Result<Vec<u8>, InputError> {
    use std::io::Read as _;
    let mut bytes = Vec::with_capacity(usize::try_from(len.min(limit) + 1).unwrap_or(0));
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(InputError::Io)?;
    if bytes.len() as u64 > limit {
        return Err(InputError::TooLarge {
            bytes: limit + 1,
            limit,
        });
    }
    Ok(bytes)
}

/// The regular file at `path`, opened, and its length (see [`read_input`]).
pub(super) fn open_input(path: &Path, limit: u64) -> Result<(std::fs::File, u64), InputError> {
    let meta = std::fs::metadata(path).map_err(InputError::Io)?;
    let kind = meta.file_type();
    if kind.is_dir() {
        return Err(InputError::Directory);
    }
    if !kind.is_file() {
        return Err(InputError::NotRegular);
    }
    if meta.len() > limit {
        return Err(InputError::TooLarge {
            bytes: meta.len(),
            limit,
        });
    }
    let file = std::fs::File::open(path).map_err(InputError::Io)?;
    Ok((file, meta.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inputs_that_cannot_be_read_are_typed_errors() {
        let dir = std::env::temp_dir().join(format!("softshadow-input-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("ten.txt");
        std::fs::write(&file, b"0123456789").unwrap();
        assert_eq!(read_input(&file, 10).unwrap(), b"0123456789");
        let e = read_input(&file, 9).unwrap_err();
        assert!(
            matches!(
                e,
                InputError::TooLarge {
                    bytes: 10,
                    limit: 9
                }
            ),
            "{e:?}"
        );
        assert_eq!(e.to_string(), "10 bytes or more, over the limit of 9 bytes");
        assert!(matches!(
            read_input(&dir, 1 << 20),
            Err(InputError::Directory)
        ));
        let missing = read_input(&dir.join("missing"), 1 << 20).unwrap_err();
        assert!(
            matches!(&missing, InputError::Io(io) if io.kind() == std::io::ErrorKind::NotFound),
            "{missing:?}"
        );
        #[cfg(unix)]
        assert!(matches!(
            read_input(Path::new("/dev/null"), 1 << 20),
            Err(InputError::NotRegular)
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
