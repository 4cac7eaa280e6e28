//! What a reader read: a file's size and the SHA-256 of its bytes, taken as the bytes go
//! by (the provenance of a study's `results.json`). Values only; the readers feed it.

use sha2::{Digest as _, Sha256};

/// A file as it was read: its size and the SHA-256 of its bytes.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct FileDigest {
    /// Size, bytes.
    pub bytes: u64,
    /// SHA-256 of the bytes, 64 lowercase hexadecimal digits.
    pub sha256: String,
}

impl FileDigest {
    /// The digest of `bytes` held in memory.
    ///
    /// ```
    /// let d = recording::FileDigest::of(b"abc");
    /// assert_eq!(d.bytes, 3);
    /// // FIPS 180-2, appendix B.1
    /// assert_eq!(d.sha256, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    /// ```
    #[must_use]
    pub fn of(bytes: &[u8]) -> Self {
        let mut hasher = Hasher::default();
        hasher.update(bytes);
        hasher.finish()
    }
}

/// A digest taken piece by piece, as a file is read.
#[derive(Debug, Clone, Default)]
pub struct Hasher {
    sha: Sha256,
    bytes: u64,
}

impl Hasher {
    /// Adds the next bytes read.
    pub fn update(&mut self, bytes: &[u8]) {
        self.sha.update(bytes);
        self.bytes += bytes.len() as u64;
    }

    /// The digest of all bytes added.
    #[must_use]
    pub fn finish(self) -> FileDigest {
        use std::fmt::Write as _;
        let hash = self.sha.finalize();
        let sha256 = hash.iter().fold(String::with_capacity(64), |mut s, b| {
            // writing to a String cannot fail
            let _ = write!(s, "{b:02x}");
            s
        });
        FileDigest {
            bytes: self.bytes,
            sha256,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_give_the_digest_of_the_whole() {
        let text = b"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
        let mut hasher = Hasher::default();
        for piece in text.chunks(7) {
            hasher.update(piece);
        }
        let d = hasher.finish();
        assert_eq!(d, FileDigest::of(text));
        // FIPS 180-2, appendix B.2
        assert_eq!(
            d.sha256,
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"
        );
        assert_eq!(d.bytes, 56);
        assert_eq!(FileDigest::of(b"").bytes, 0);
    }
}
