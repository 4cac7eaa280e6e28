//! The streaming pass over one revolution: the sums of the normal equations.
//!
//! For the basis `1, cos kθ, sin kθ (k = 1…N)` every entry of the normal matrix is a sum of
//! `cos mθ` or `sin mθ` with `m ≤ 2N` (product-to-sum identities), so one pass accumulates
//! `Σ cos mθ, Σ sin mθ (m ≤ 2N)`, the data products `Σ y cos kθ, Σ y sin kθ (k ≤ N)`, `Σ y`,
//! `Σ y²` and, with a drift term, the products with the normalised time `τ`. The angle of each
//! sample comes from the data, so `cos θ, sin θ` are computed per sample (see `sincos`) and the
//! higher orders follow by the Chebyshev recurrence over the order at that sample,
//! `cos kθ = 2 cos θ·cos (k−1)θ − cos (k−2)θ` (likewise for `sin kθ`). No design matrix is
//! formed.
//!
//! Samples are processed in blocks of `BLOCK`: first `cos θ, sin θ` of every sample of the
//! block, then the orders `k = 2…2N` in runs of a few orders: a run reads the two stored
//! orders below its first, forms its orders by the recurrence in registers, adds each to its
//! sums there, and stores only its last two orders for the next run (`DATA_RUN` data orders
//! or `MOMENT_RUN` moment orders per run, as many as keep the sums in the CPU's registers).
//! Every sum keeps `LANES` independent lanes (lane `l` takes the samples `i ≡ l mod LANES`,
//! in order), which the compiler turns into SIMD, and the result is bit for bit that of
//! adding `LANES` samples at a time (a unit test checks it). On the AVX2 machine of
//! docs/PERFORMANCE.md the 2.88 M-sample fit took 28–31 ms with every sum updated per
//! sample (some 50 accumulators in flight, more than the 16 vector registers), 19 ms with
//! one order per loop and eight lanes, and 14–16 ms with runs of orders and four lanes
//! (half the loads and stores of the basis). `pulp` dispatches at run time to the widest
//! instruction set the CPU has (the workspace forbids `unsafe`, so no intrinsics here).

// Lane loops index several arrays at once; that is what vectorises.
#![allow(clippy::needless_range_loop)]

use crate::sincos::sin_cos;

/// Largest supported Fourier order.
pub const MAX_ORDER: usize = 8;
/// Length of the `Σ cos mθ` / `Σ sin mθ` arrays, `m = 0…2·MAX_ORDER`.
pub(crate) const MOMENTS: usize = 2 * MAX_ORDER + 1;
/// Samples per accumulation step: lane `l` of every sum takes the samples `i ≡ l (mod LANES)`
/// in order, so the result does not depend on how the pass is blocked.
const LANES: usize = 4;
/// Samples per block: the basis `cos kθ, sin kθ` of a block is formed first, then each sum
/// runs over the block with its lanes held in registers (a multiple of `LANES`).
const BLOCK: usize = 64;
/// Data orders (`k ≤ N`) formed per loop over a block without drift (four sums each).
const DATA_RUN: usize = 2;
/// Moment orders (`N < k ≤ 2N`) formed per loop over a block (two sums each).
const MOMENT_RUN: usize = 4;

/// How a sample's angle follows from its source value `x`: `θ = (x − shift)·scale + offset`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct AngleMap {
    pub(crate) shift: f64,
    pub(crate) scale: f64,
    pub(crate) offset: f64,
}

/// Centring of the data: `y − y_ref` and `τ = (t − t_mid)·t_inv_half ∈ [−1, 1]`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Centring {
    pub(crate) y_ref: f64,
    pub(crate) t_mid: f64,
    pub(crate) t_inv_half: f64,
}

/// Sums over one revolution (centred data `y`, normalised time `τ`).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Sums {
    /// Number of samples.
    pub(crate) n: f64,
    /// `Σ cos mθ`, `m = 0…2N` (`[0]` is `n`).
    pub(crate) cos: [f64; MOMENTS],
    /// `Σ sin mθ`, `m = 0…2N` (`[0]` is 0).
    pub(crate) sin: [f64; MOMENTS],
    /// `Σ y cos kθ`, `k = 0…N` (`[0]` is `Σ y`).
    pub(crate) y_cos: [f64; MAX_ORDER + 1],
    /// `Σ y sin kθ`, `k = 0…N` (`[0]` is 0).
    pub(crate) y_sin: [f64; MAX_ORDER + 1],
    /// `Σ y²`.
    pub(crate) yy: f64,
    /// `Σ τ cos kθ`, `k = 0…N` (`[0]` is `Σ τ`); zero without drift.
    pub(crate) tau_cos: [f64; MAX_ORDER + 1],
    /// `Σ τ sin kθ`, `k = 0…N`; zero without drift.
    pub(crate) tau_sin: [f64; MAX_ORDER + 1],
    /// `Σ τ²`.
    pub(crate) tau_tau: f64,
    /// `Σ τ y`.
    pub(crate) tau_y: f64,
}

impl Sums {
    /// All sums zero, for `n` samples.
    pub(crate) const fn empty(n: usize) -> Self {
        Self {
            n: n as f64,
            cos: [0.0; MOMENTS],
            sin: [0.0; MOMENTS],
            y_cos: [0.0; MAX_ORDER + 1],
            y_sin: [0.0; MAX_ORDER + 1],
            yy: 0.0,
            tau_cos: [0.0; MAX_ORDER + 1],
            tau_sin: [0.0; MAX_ORDER + 1],
            tau_tau: 0.0,
            tau_y: 0.0,
        }
    }
}

/// Per-lane accumulators.
struct Acc<const W: usize> {
    cos: [[f64; W]; MOMENTS],
    sin: [[f64; W]; MOMENTS],
    y_cos: [[f64; W]; MAX_ORDER + 1],
    y_sin: [[f64; W]; MAX_ORDER + 1],
    yy: [f64; W],
    tau_cos: [[f64; W]; MAX_ORDER + 1],
    tau_sin: [[f64; W]; MAX_ORDER + 1],
    tau_tau: [f64; W],
    tau_y: [f64; W],
}

impl<const W: usize> Acc<W> {
    const ZERO: Self = Self {
        cos: [[0.0; W]; MOMENTS],
        sin: [[0.0; W]; MOMENTS],
        y_cos: [[0.0; W]; MAX_ORDER + 1],
        y_sin: [[0.0; W]; MAX_ORDER + 1],
        yy: [0.0; W],
        tau_cos: [[0.0; W]; MAX_ORDER + 1],
        tau_sin: [[0.0; W]; MAX_ORDER + 1],
        tau_tau: [0.0; W],
        tau_y: [0.0; W],
    };

    /// Adds `W` samples.
    #[inline(always)]
    fn add<const N: usize, const DRIFT: bool>(
        &mut self,
        x: &[f64; W],
        y: &[f64; W],
        t: &[f64; W],
        map: AngleMap,
        centre: Centring,
    ) {
        let mut c1 = [0.0; W];
        let mut s1 = [0.0; W];
        let mut yv = [0.0; W];
        let mut tau = [0.0; W];
        for l in 0..W {
            let theta = (x[l] - map.shift).mul_add(map.scale, map.offset);
            (s1[l], c1[l]) = sin_cos(theta);
            yv[l] = y[l] - centre.y_ref;
            if DRIFT {
                tau[l] = (t[l] - centre.t_mid) * centre.t_inv_half;
            }
        }
        for l in 0..W {
            self.yy[l] = yv[l].mul_add(yv[l], self.yy[l]);
            self.y_cos[0][l] += yv[l];
            self.cos[1][l] += c1[l];
            self.sin[1][l] += s1[l];
            self.y_cos[1][l] = yv[l].mul_add(c1[l], self.y_cos[1][l]);
            self.y_sin[1][l] = yv[l].mul_add(s1[l], self.y_sin[1][l]);
            if DRIFT {
                self.tau_cos[0][l] += tau[l];
                self.tau_tau[l] = tau[l].mul_add(tau[l], self.tau_tau[l]);
                self.tau_y[l] = tau[l].mul_add(yv[l], self.tau_y[l]);
                self.tau_cos[1][l] = tau[l].mul_add(c1[l], self.tau_cos[1][l]);
                self.tau_sin[1][l] = tau[l].mul_add(s1[l], self.tau_sin[1][l]);
            }
        }
        // cos kθ and sin kθ for k = 0…2N by the Chebyshev recurrence, each order a whole
        // array of lanes (no rotation of temporaries through memory, which stalls the
        // store-to-load forwarding on some CPUs).
        let mut cs = [[0.0; W]; MOMENTS];
        let mut sn = [[0.0; W]; MOMENTS];
        cs[0] = [1.0; W];
        cs[1] = c1;
        sn[1] = s1;
        let mut two_c1 = [0.0; W];
        for l in 0..W {
            two_c1[l] = c1[l] + c1[l];
        }
        for k in 2..=2 * N {
            for l in 0..W {
                cs[k][l] = two_c1[l].mul_add(cs[k - 1][l], -cs[k - 2][l]);
                sn[k][l] = two_c1[l].mul_add(sn[k - 1][l], -sn[k - 2][l]);
            }
        }
        // Orders 2…N: moments, data products (and drift products).
        for k in 2..=N {
            for l in 0..W {
                self.cos[k][l] += cs[k][l];
                self.sin[k][l] += sn[k][l];
                self.y_cos[k][l] = yv[l].mul_add(cs[k][l], self.y_cos[k][l]);
                self.y_sin[k][l] = yv[l].mul_add(sn[k][l], self.y_sin[k][l]);
                if DRIFT {
                    self.tau_cos[k][l] = tau[l].mul_add(cs[k][l], self.tau_cos[k][l]);
                    self.tau_sin[k][l] = tau[l].mul_add(sn[k][l], self.tau_sin[k][l]);
                }
            }
        }
        // Orders N+1…2N: moments only.
        for k in N + 1..=2 * N {
            for l in 0..W {
                self.cos[k][l] += cs[k][l];
                self.sin[k][l] += sn[k][l];
            }
        }
    }

    /// Adds the samples of one block (`x.len()` a multiple of `W`, at most `BLOCK`), with
    /// the same operations in the same order per lane as [`Acc::add`], so the sums are
    /// bit for bit those of adding the samples `W` at a time.
    #[inline(always)]
    fn add_block<const N: usize, const DRIFT: bool>(
        &mut self,
        basis: &mut Basis,
        x: &[f64],
        y: &[f64],
        t: &[f64],
        map: AngleMap,
        centre: Centring,
    ) {
        let len = x.len().min(BLOCK);
        let (x, y) = (&x[..len], &y[..len]);
        let t = if DRIFT { &t[..len] } else { x };
        let Basis {
            cos,
            sin,
            y: yv,
            tau,
        } = basis;
        for j in 0..len {
            let theta = (x[j] - map.shift).mul_add(map.scale, map.offset);
            (sin[1][j], cos[1][j]) = sin_cos(theta);
            yv[j] = y[j] - centre.y_ref;
            if DRIFT {
                tau[j] = (t[j] - centre.t_mid) * centre.t_inv_half;
            }
        }
        // Order 1 and the data's own sums, several per loop: each lane of each sum is a
        // chain of dependent adds, so a loop over one sum waits on the adder's latency.
        let (yv, tau) = (&yv[..len], &tau[..len]);
        let mut a = [self.cos[1], self.sin[1], self.y_cos[0]];
        lane_sums(&mut a, [&cos[1][..len], &sin[1][..len], yv]);
        [self.cos[1], self.sin[1], self.y_cos[0]] = a;
        let mut a = [self.y_cos[1], self.y_sin[1], self.yy];
        lane_dots(&mut a, yv, [&cos[1][..len], &sin[1][..len], yv]);
        [self.y_cos[1], self.y_sin[1], self.yy] = a;
        if DRIFT {
            let mut a = [self.tau_cos[0]];
            lane_sums(&mut a, [tau]);
            [self.tau_cos[0]] = a;
            let mut a = [self.tau_tau, self.tau_y, self.tau_cos[1], self.tau_sin[1]];
            lane_dots(&mut a, tau, [tau, yv, &cos[1][..len], &sin[1][..len]]);
            [self.tau_tau, self.tau_y, self.tau_cos[1], self.tau_sin[1]] = a;
        }
        // Orders 2…2N, several per loop: the recurrence runs in registers from the two
        // stored orders below the first of a run, and only the run's last two orders are
        // stored for the next run. A run holds as many orders as keep its sums in
        // registers: data orders (k ≤ N) carry four or six sums each, moment orders two.
        let data_run = if DRIFT { 1 } else { DATA_RUN };
        let mut k = 2;
        while k <= 2 * N {
            let (data, last) = if k <= N {
                (true, N.min(k + data_run - 1))
            } else {
                (false, (2 * N).min(k + MOMENT_RUN - 1))
            };
            let store = last < 2 * N;
            let run = last + 1 - k;
            macro_rules! go {
                ($p:literal) => {
                    if data {
                        self.order_run::<$p, true, DRIFT>(basis, k, len, store)
                    } else {
                        self.order_run::<$p, false, false>(basis, k, len, store)
                    }
                };
            }
            match run {
                1 => go!(1),
                2 => go!(2),
                3 => go!(3),
                _ => go!(4),
            }
            k = last + 1;
        }
    }

    /// Forms the orders `k0 … k0+P−1` of a block by the recurrence, with the two orders below
    /// `k0` read from `basis`, and adds them lane by lane in sample order to their sums (with
    /// the data products for `DATA`, the drift products as well for `DRIFT`), keeping each
    /// order's values in registers; with `store`, the run's last two orders go back into
    /// `basis` for the next run. Per lane the operations are those of [`Acc::add`].
    #[inline(always)]
    fn order_run<const P: usize, const DATA: bool, const DRIFT: bool>(
        &mut self,
        basis: &mut Basis,
        k0: usize,
        len: usize,
        store: bool,
    ) {
        let Basis { cos, sin, y, tau } = basis;
        let mut a = [[[0.0; W]; 6]; P];
        for p in 0..P {
            a[p][0] = self.cos[k0 + p];
            a[p][1] = self.sin[k0 + p];
            if DATA {
                a[p][2] = self.y_cos[k0 + p];
                a[p][3] = self.y_sin[k0 + p];
                if DRIFT {
                    a[p][4] = self.tau_cos[k0 + p];
                    a[p][5] = self.tau_sin[k0 + p];
                }
            }
        }
        let mut j = 0;
        while j + W <= len {
            let mut two_c1 = [0.0; W];
            let (mut cp1, mut cp2, mut sp1, mut sp2) = ([0.0; W], [0.0; W], [0.0; W], [0.0; W]);
            let (mut yv, mut tv) = ([0.0; W], [0.0; W]);
            for l in 0..W {
                let i = j + l;
                two_c1[l] = cos[1][i] + cos[1][i];
                cp1[l] = cos[k0 - 1][i];
                cp2[l] = cos[k0 - 2][i];
                sp1[l] = sin[k0 - 1][i];
                sp2[l] = sin[k0 - 2][i];
                if DATA {
                    yv[l] = y[i];
                    if DRIFT {
                        tv[l] = tau[i];
                    }
                }
            }
            for p in 0..P {
                let mut c = [0.0; W];
                let mut s = [0.0; W];
                for l in 0..W {
                    c[l] = two_c1[l].mul_add(cp1[l], -cp2[l]);
                    s[l] = two_c1[l].mul_add(sp1[l], -sp2[l]);
                    a[p][0][l] += c[l];
                    a[p][1][l] += s[l];
                    if DATA {
                        a[p][2][l] = yv[l].mul_add(c[l], a[p][2][l]);
                        a[p][3][l] = yv[l].mul_add(s[l], a[p][3][l]);
                        if DRIFT {
                            a[p][4][l] = tv[l].mul_add(c[l], a[p][4][l]);
                            a[p][5][l] = tv[l].mul_add(s[l], a[p][5][l]);
                        }
                    }
                }
                (cp2, cp1, sp2, sp1) = (cp1, c, sp1, s);
            }
            if store {
                // Element by element: `copy_from_slice` here was measured slower (a call
                // per four values instead of vector stores).
                let k = k0 + P - 1;
                #[allow(clippy::manual_memcpy)]
                for l in 0..W {
                    cos[k][j + l] = cp1[l];
                    sin[k][j + l] = sp1[l];
                    cos[k - 1][j + l] = cp2[l];
                    sin[k - 1][j + l] = sp2[l];
                }
            }
            j += W;
        }
        for p in 0..P {
            self.cos[k0 + p] = a[p][0];
            self.sin[k0 + p] = a[p][1];
            if DATA {
                self.y_cos[k0 + p] = a[p][2];
                self.y_sin[k0 + p] = a[p][3];
                if DRIFT {
                    self.tau_cos[k0 + p] = a[p][4];
                    self.tau_sin[k0 + p] = a[p][5];
                }
            }
        }
    }

    /// Adds the lanes into `sums`.
    fn reduce_into(&self, sums: &mut Sums) {
        let add = |dst: &mut [f64], src: &[[f64; W]]| {
            for (d, s) in dst.iter_mut().zip(src) {
                *d += s.iter().sum::<f64>();
            }
        };
        add(&mut sums.cos, &self.cos);
        add(&mut sums.sin, &self.sin);
        add(&mut sums.y_cos, &self.y_cos);
        add(&mut sums.y_sin, &self.y_sin);
        add(&mut sums.tau_cos, &self.tau_cos);
        add(&mut sums.tau_sin, &self.tau_sin);
        sums.yy += self.yy.iter().sum::<f64>();
        sums.tau_tau += self.tau_tau.iter().sum::<f64>();
        sums.tau_y += self.tau_y.iter().sum::<f64>();
    }
}

/// The basis of one block: `cos kθ`, `sin kθ` (`k = 0…2N`), the centred data and `τ` of
/// each sample.
struct Basis {
    cos: [[f64; BLOCK]; MOMENTS],
    sin: [[f64; BLOCK]; MOMENTS],
    y: [f64; BLOCK],
    tau: [f64; BLOCK],
}

impl Basis {
    fn new() -> Self {
        let mut cos = [[0.0; BLOCK]; MOMENTS];
        cos[0] = [1.0; BLOCK];
        Self {
            cos,
            sin: [[0.0; BLOCK]; MOMENTS],
            y: [0.0; BLOCK],
            tau: [0.0; BLOCK],
        }
    }
}

/// `acc[g][l] += v[g][i]` for the samples `i ≡ l (mod W)`, in order, for `G` sums at once.
#[inline(always)]
fn lane_sums<const W: usize, const G: usize>(acc: &mut [[f64; W]; G], v: [&[f64]; G]) {
    let len = v[0].len();
    let mut a = *acc;
    let mut j = 0;
    while j + W <= len {
        for g in 0..G {
            let chunk = &v[g][j..j + W];
            for l in 0..W {
                a[g][l] += chunk[l];
            }
        }
        j += W;
    }
    *acc = a;
}

/// `acc[g][l] = u[i]·v[g][i] + acc[g][l]` (fused) for the samples `i ≡ l (mod W)`, in
/// order, for `G` sums at once.
#[inline(always)]
fn lane_dots<const W: usize, const G: usize>(acc: &mut [[f64; W]; G], u: &[f64], v: [&[f64]; G]) {
    let len = u.len();
    let mut a = *acc;
    let mut j = 0;
    while j + W <= len {
        let cu = &u[j..j + W];
        for g in 0..G {
            let cv = &v[g][j..j + W];
            for l in 0..W {
                a[g][l] = cu[l].mul_add(cv[l], a[g][l]);
            }
        }
        j += W;
    }
    *acc = a;
}

/// The pass for a fixed order and drift flag.
#[inline(always)]
fn pass<const N: usize, const DRIFT: bool>(
    x: &[f64],
    y: &[f64],
    t: &[f64],
    map: AngleMap,
    centre: Centring,
) -> Sums {
    debug_assert_eq!(x.len(), y.len());
    debug_assert!(!DRIFT || t.len() == y.len());
    let n = y.len();
    let body = n - n % LANES;
    let mut wide = Acc::<LANES>::ZERO;
    let mut basis = Basis::new();
    for start in (0..body).step_by(BLOCK) {
        let end = (start + BLOCK).min(body);
        let ts = if DRIFT {
            &t[start..end]
        } else {
            &x[start..end]
        };
        wide.add_block::<N, DRIFT>(&mut basis, &x[start..end], &y[start..end], ts, map, centre);
    }
    let mut narrow = Acc::<1>::ZERO;
    for i in body..n {
        let ts = if DRIFT { [t[i]] } else { [0.0] };
        narrow.add::<N, DRIFT>(&[x[i]], &[y[i]], &ts, map, centre);
    }
    let mut sums = Sums::empty(n);
    wide.reduce_into(&mut sums);
    narrow.reduce_into(&mut sums);
    sums.cos[0] = sums.n;
    sums
}

/// Accumulates the sums of one revolution, dispatching on the order, the drift flag and
/// the CPU's instruction set.
///
/// `x` is the angle source of each sample (encoder angle or time), `y` the gap and `t` the
/// time (read only with `drift`). `order` must be in `1..=MAX_ORDER` (checked by the caller).
pub(crate) fn accumulate(
    order: usize,
    drift: bool,
    x: &[f64],
    y: &[f64],
    t: &[f64],
    map: AngleMap,
    centre: Centring,
) -> Sums {
    let arch = pulp::Arch::new();
    macro_rules! dispatch {
        ($($n:literal)*) => {
            match (order, drift) {
                $(
                    ($n, false) => arch.dispatch(Pass::<$n, false> { x, y, t, map, centre }),
                    ($n, true) => arch.dispatch(Pass::<$n, true> { x, y, t, map, centre }),
                )*
                _ => unreachable!("order {order} checked by the caller"),
            }
        };
    }
    dispatch!(1 2 3 4 5 6 7 8)
}

/// The pass as a `pulp` operation: `with_simd` is inlined into the function that `pulp`
/// compiles with the CPU's features, and `pass` (inlined into it) is vectorised for them.
struct Pass<'a, const N: usize, const DRIFT: bool> {
    x: &'a [f64],
    y: &'a [f64],
    t: &'a [f64],
    map: AngleMap,
    centre: Centring,
}

impl<const N: usize, const DRIFT: bool> pulp::WithSimd for Pass<'_, N, DRIFT> {
    type Output = Sums;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> Sums {
        pass::<N, DRIFT>(self.x, self.y, self.t, self.map, self.centre)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Direct evaluation with libm, for comparison.
    fn direct(order: usize, x: &[f64], y: &[f64], t: &[f64], map: AngleMap, c: Centring) -> Sums {
        let mut s = Sums::empty(x.len());
        for i in 0..x.len() {
            let theta = (x[i] - map.shift) * map.scale + map.offset;
            let yv = y[i] - c.y_ref;
            let tau = (t[i] - c.t_mid) * c.t_inv_half;
            s.yy += yv * yv;
            s.tau_tau += tau * tau;
            s.tau_y += tau * yv;
            for m in 0..=2 * order {
                let (sm, cm) = (m as f64 * theta).sin_cos();
                s.cos[m] += cm;
                s.sin[m] += sm;
                if m <= order {
                    s.y_cos[m] += yv * cm;
                    s.y_sin[m] += yv * sm;
                    s.tau_cos[m] += tau * cm;
                    s.tau_sin[m] += tau * sm;
                }
            }
        }
        s
    }

    /// `n` samples of an irregular angle source, a gap and a time, with a map and centring.
    fn samples(n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>, AngleMap, Centring) {
        let x = (0..n)
            .map(|i| 0.3 + 0.0071 * i as f64 + 1e-3 * (i as f64).sin())
            .collect();
        let y = (0..n).map(|i| 5.0 + (0.37 * i as f64).cos()).collect();
        let t = (0..n).map(|i| 0.001 * i as f64).collect();
        let map = AngleMap {
            shift: 0.1,
            scale: 1.3,
            offset: -0.2,
        };
        let centre = Centring {
            y_ref: 5.0,
            t_mid: 0.5,
            t_inv_half: 2.0,
        };
        (x, y, t, map, centre)
    }

    /// The pass as it was before blocking: `LANES` samples at a time through [`Acc::add`].
    fn by_lanes<const N: usize, const DRIFT: bool>(
        x: &[f64],
        y: &[f64],
        t: &[f64],
        map: AngleMap,
        centre: Centring,
    ) -> Sums {
        let n = y.len();
        let body = n - n % LANES;
        let mut wide = Acc::<LANES>::ZERO;
        for i in (0..body).step_by(LANES) {
            let xs: &[f64; LANES] = x[i..i + LANES].try_into().unwrap();
            let ys: &[f64; LANES] = y[i..i + LANES].try_into().unwrap();
            let ts: &[f64; LANES] = t[i..i + LANES].try_into().unwrap();
            wide.add::<N, DRIFT>(xs, ys, ts, map, centre);
        }
        let mut narrow = Acc::<1>::ZERO;
        for i in body..n {
            narrow.add::<N, DRIFT>(&[x[i]], &[y[i]], &[t[i]], map, centre);
        }
        let mut sums = Sums::empty(n);
        wide.reduce_into(&mut sums);
        narrow.reduce_into(&mut sums);
        sums.cos[0] = sums.n;
        sums
    }

    /// Blocking changes no bit: every lane sums the same samples in the same order.
    #[test]
    fn blocked_pass_equals_lane_by_lane_bit_for_bit() {
        for n in [7, 64, 200, 4099] {
            let (x, y, t, map, centre) = samples(n);
            assert_eq!(
                pass::<4, false>(&x, &y, &t, map, centre),
                by_lanes::<4, false>(&x, &y, &t, map, centre),
                "n = {n}"
            );
            assert_eq!(
                pass::<3, true>(&x, &y, &t, map, centre),
                by_lanes::<3, true>(&x, &y, &t, map, centre),
                "n = {n}"
            );
            assert_eq!(
                pass::<8, true>(&x, &y, &t, map, centre),
                by_lanes::<8, true>(&x, &y, &t, map, centre),
                "n = {n}"
            );
        }
    }

    #[test]
    fn recurrence_matches_direct_sums_for_every_order() {
        let n = 1003; // not a multiple of the lane width
        let (x, y, t, map, centre) = samples(n);
        for order in 1..=MAX_ORDER {
            let got = accumulate(order, true, &x, &y, &t, map, centre);
            let want = direct(order, &x, &y, &t, map, centre);
            let close = |a: &[f64], b: &[f64]| {
                a.iter()
                    .zip(b)
                    .all(|(a, b)| (a - b).abs() <= 1e-10 * n as f64)
            };
            assert!(
                close(&got.cos[..=2 * order], &want.cos[..=2 * order]),
                "order {order}"
            );
            assert!(
                close(&got.sin[..=2 * order], &want.sin[..=2 * order]),
                "order {order}"
            );
            assert!(
                close(&got.y_cos[..=order], &want.y_cos[..=order]),
                "order {order}"
            );
            assert!(
                close(&got.y_sin[..=order], &want.y_sin[..=order]),
                "order {order}"
            );
            assert!(
                close(&got.tau_cos[..=order], &want.tau_cos[..=order]),
                "order {order}"
            );
            assert!(
                close(&got.tau_sin[..=order], &want.tau_sin[..=order]),
                "order {order}"
            );
            assert!(close(
                &[got.yy, got.tau_tau, got.tau_y],
                &[want.yy, want.tau_tau, want.tau_y]
            ));
            // Without drift the drift sums stay zero and the others are unchanged.
            let plain = accumulate(order, false, &x, &y, &t, map, centre);
            assert_eq!(plain.cos, got.cos);
            assert_eq!(plain.y_sin, got.y_sin);
            assert_eq!(plain.tau_y, 0.0);
        }
    }
}
