//! Decoding the little-endian numeric samples both binary formats store, in blocks on all
//! cores, with the finiteness scan done while each block is in cache.

/// The numeric sample types both formats store, little-endian.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum NumType {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
}

impl NumType {
    /// Bytes per value.
    pub(crate) const fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::I64 | Self::U64 | Self::F64 => 8,
        }
    }
}

/// Values decoded per block: blocks of a long channel are decoded on all cores (rayon).
pub(crate) const BLOCK: usize = 1 << 16;

/// Fills `out` with values of type `ty` starting at `bytes[0]`, each `stride` bytes after
/// the previous; returns how many were in `bytes` (the caller has checked that all are) and
/// whether all of them are finite (each block is scanned while it is in cache).
/// Give it memory from `vec![0.0; n]`, which the allocator takes zeroed from the system
/// without writing it; long outputs are filled in blocks on all cores (rayon).
pub(crate) fn decode(out: &mut [f64], bytes: &[u8], ty: NumType, stride: usize) -> (usize, bool) {
    let size = ty.size();
    if stride < size {
        return (0, true);
    }
    // Whole values in `bytes`.
    let fit = if bytes.len() < size {
        0
    } else {
        (bytes.len() - size) / stride + 1
    };
    let count = out.len().min(fit);
    let out = &mut out[..count];
    let finite = if count <= BLOCK {
        decode_into(out, bytes, ty, stride)
    } else {
        use rayon::prelude::*;
        // `reduce`, not `all`: every block is decoded, whatever the others hold.
        out.par_chunks_mut(BLOCK)
            .enumerate()
            .map(|(k, block)| decode_into(block, &bytes[k * BLOCK * stride..], ty, stride))
            .reduce(|| true, |a, b| a && b)
    };
    (count, finite)
}

/// Fills `out` with values of type `ty` from `bytes`, `stride` bytes apart (all in `bytes`);
/// whether all are finite.
fn decode_into(out: &mut [f64], bytes: &[u8], ty: NumType, stride: usize) -> bool {
    fn run<const N: usize>(
        out: &mut [f64],
        bytes: &[u8],
        stride: usize,
        f: impl Fn([u8; N]) -> f64,
    ) {
        let value = |c: &[u8]| <[u8; N]>::try_from(&c[..N]).map_or(f64::NAN, &f);
        if stride == N {
            // Contiguous: a loop the compiler vectorises.
            for (o, c) in out.iter_mut().zip(bytes.chunks_exact(N)) {
                *o = value(c);
            }
        } else {
            for (o, c) in out.iter_mut().zip(bytes.chunks(stride)) {
                if c.len() >= N {
                    *o = value(c);
                }
            }
        }
    }
    match ty {
        NumType::I8 => run::<1>(out, bytes, stride, |b| f64::from(i8::from_le_bytes(b))),
        NumType::U8 => run::<1>(out, bytes, stride, |b| f64::from(b[0])),
        NumType::I16 => run::<2>(out, bytes, stride, |b| f64::from(i16::from_le_bytes(b))),
        NumType::U16 => run::<2>(out, bytes, stride, |b| f64::from(u16::from_le_bytes(b))),
        NumType::I32 => run::<4>(out, bytes, stride, |b| f64::from(i32::from_le_bytes(b))),
        NumType::U32 => run::<4>(out, bytes, stride, |b| f64::from(u32::from_le_bytes(b))),
        // 64-bit integers above 2^53 round to the nearest double.
        NumType::I64 => run::<8>(out, bytes, stride, |b| i64::from_le_bytes(b) as f64),
        NumType::U64 => run::<8>(out, bytes, stride, |b| u64::from_le_bytes(b) as f64),
        NumType::F32 => run::<4>(out, bytes, stride, |b| f64::from(f32::from_le_bytes(b))),
        NumType::F64 => run::<8>(out, bytes, stride, f64::from_le_bytes),
    }
    first_non_finite(out).is_none()
}

/// The index of the first value that is NaN or infinite, if any (a branch-free scan of
/// eight lanes, then a search only when one is found).
pub(crate) fn first_non_finite(values: &[f64]) -> Option<usize> {
    if values.len() > BLOCK {
        use rayon::prelude::*;
        return values
            .par_chunks(BLOCK)
            .enumerate()
            .filter_map(|(k, block)| first_non_finite(block).map(|i| k * BLOCK + i))
            .min();
    }
    let mut lanes = [0.0f64; 8];
    let chunks = values.chunks_exact(8);
    let rest = chunks.remainder();
    for c in chunks {
        for (l, &x) in lanes.iter_mut().zip(c) {
            // x · 0 is 0 for a finite x and NaN otherwise.
            *l += x * 0.0;
        }
    }
    let tail: f64 = rest.iter().map(|&x| x * 0.0).sum();
    if lanes.iter().sum::<f64>() + tail == 0.0 {
        None
    } else {
        values.iter().position(|x| !x.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decode_contiguous_and_strided() {
        let bytes: Vec<u8> = [1.5f64, -2.0, 3.25]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let mut out = vec![0.0; 3];
        assert_eq!(decode(&mut out, &bytes, NumType::F64, 8), (3, true));
        assert_eq!(out, [1.5, -2.0, 3.25]);
        assert_eq!(decode(&mut out[..2], &bytes, NumType::F64, 16), (2, true));
        assert_eq!(out[..2], [1.5, 3.25]);
        // Only whole values in the bytes.
        assert_eq!(decode(&mut out, &bytes[..20], NumType::F64, 8).0, 2);
        assert_eq!(
            decode(&mut out[..2], &[0xff, 0x7f, 0x00, 0x80], NumType::I16, 2),
            (2, true)
        );
        assert_eq!(out[..2], [32767.0, -32768.0]);
        // Long outputs are decoded in blocks on several threads, in order.
        let n = 3 * BLOCK + 5;
        let bytes: Vec<u8> = (0..n).flat_map(|i| (i as f32).to_le_bytes()).collect();
        let mut out = vec![0.0; n];
        assert_eq!(decode(&mut out, &bytes, NumType::F32, 4), (n, true));
        assert!(out.iter().enumerate().all(|(i, &x)| x == i as f64));
        let mut out = vec![0.0; n / 2];
        assert_eq!(decode(&mut out, &bytes, NumType::F32, 8), (n / 2, true));
        assert!(out.iter().enumerate().all(|(i, &x)| x == (2 * i) as f64));
        // A NaN in any block is reported, and every block is still decoded.
        let mut bytes = bytes;
        bytes[4 * (2 * BLOCK + 3)..][..4].copy_from_slice(&f32::NAN.to_le_bytes());
        let mut out = vec![0.0; n];
        assert_eq!(decode(&mut out, &bytes, NumType::F32, 4), (n, false));
        assert_eq!(out[n - 1], (n - 1) as f64);
        assert!(out[2 * BLOCK + 3].is_nan());
    }

    #[test]
    fn non_finite_found_in_any_lane() {
        let mut v = vec![1.0; 21];
        assert_eq!(first_non_finite(&v), None);
        for i in [0, 7, 8, 20] {
            v[i] = f64::INFINITY;
            assert_eq!(first_non_finite(&v), Some(i));
            v[i] = 1.0;
        }
    }
}
