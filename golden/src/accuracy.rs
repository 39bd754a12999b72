//! Accuracy of every approximation over its stated domain, measured by dense sampling with
//! golden-section refinement of the extremum, beside the sources' claims.
//!
//! Error definitions:
//! - normalizer f(K) ≈ 1/√K: relative error of the normalized length, √K·f(K) − 1, K ∈ [0.499, 1];
//! - 1/√(M+1) forms: relative error √(M+1)·f(M) − 1, M ∈ [−0.5, 0];
//! - constants (1/3, 1/(k+1) by shifts): relative error (approx − exact)/exact;
//! - W(n, γ) and Schlick vs cos^n γ: absolute error, i.e. relative to the highlight's peak
//!   value 1 (relative errors diverge in the tail, where cos^n γ → 0). The **centre** is where
//!   cos^n γ ≥ 1/2 (the highlight inside its half-maximum), the **fall-off** ("blooming") is
//!   where cos^n γ < 1/2, γ ∈ [0, 90°]. The error grows with n, so n = 1000 is the worst case;
//!   n = 50 is the default scene.
//!
//! Also here: the derivation of the fitted coefficients ([`derive_tangent_fit`]).

use crate::units::normalizer::{self, Coeffs};
use crate::{shading::brdf, shading::cubic, shading::fast};
use serde::Serialize;

/// Samples of the dense scan (endpoints included).
pub const SAMPLES: usize = 100_001;

/// A located extremum of an error function.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Extremum {
    /// The signed error value where |error| is largest.
    pub value: f64,
    /// Where it occurs.
    pub at: f64,
}

/// Largest |f| on [lo, hi]: dense scan of `samples` points, then golden-section refinement of
/// |f| between the neighbours of the best sample.
pub fn max_abs_with(f: impl Fn(f64) -> f64, lo: f64, hi: f64, samples: usize) -> Extremum {
    let n = samples.max(3);
    let x_of = |i: usize| lo + (hi - lo) * i as f64 / (n - 1) as f64;
    let mut best = (0usize, f(lo).abs());
    for i in 1..n {
        let v = f(x_of(i)).abs();
        if v > best.1 {
            best = (i, v);
        }
    }
    let (mut a, mut b) = (
        x_of(best.0.saturating_sub(1)),
        x_of((best.0 + 1).min(n - 1)),
    );
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..100 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if f(c).abs() > f(d).abs() {
            b = d;
        } else {
            a = c;
        }
    }
    let mid = (a + b) / 2.0;
    let at = if f(mid).abs() > best.1 {
        mid
    } else {
        x_of(best.0)
    };
    Extremum { value: f(at), at }
}

/// [`max_abs_with`] at [`SAMPLES`] points.
pub fn max_abs(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Extremum {
    max_abs_with(f, lo, hi, SAMPLES)
}

/// Relative error of the normalizer: √K·f(K) − 1.
pub fn normalizer_error(c: Coeffs, k: f64) -> f64 {
    k.sqrt() * normalizer::scale(k, c) - 1.0
}

/// Relative error of a 1/√(M+1) form (c2, c1, c0 in M): √(M+1)·f(M) − 1.
pub fn inv_sqrt_error(c: Coeffs, m: f64) -> f64 {
    (m + 1.0).sqrt() * normalizer::scale(m, c) - 1.0
}

/// Max relative error of the normalizer on its domain.
pub fn normalizer_max(c: Coeffs) -> Extremum {
    let (lo, hi) = normalizer::K_DOMAIN;
    max_abs(|k| normalizer_error(c, k), lo, hi)
}

/// Max relative error of a 1/√(M+1) form on M ∈ [−0.5, 0].
pub fn inv_sqrt_max(c: Coeffs) -> Extremum {
    let (lo, hi) = fast::M_DOMAIN;
    max_abs(|m| inv_sqrt_error(c, m), lo, hi)
}

/// Derivation of the fitted forms: g(u) = 1 − u/2 + c·u² ≈ 1/√(1+u) is exact in value and
/// slope at u = 0; c is chosen to minimize max |√(1+u)·g(u) − 1| over u ∈ [lo, 0]. That max is
/// convex in c (a maximum of functions affine in c), so a golden-section search in c is exact
/// up to its tolerance. Returns the unrounded c. Normalizer: u = K − 1, lo = −0.501;
/// fast: u = M, lo = −0.5.
pub fn derive_tangent_fit(lo: f64) -> f64 {
    let err = |c: f64| {
        max_abs_with(
            |u| (1.0 + u).sqrt() * (1.0 - u / 2.0 + c * u * u) - 1.0,
            lo,
            0.0,
            4001,
        )
        .value
        .abs()
    };
    let (mut a, mut b) = (0.375, 1.0);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let (c1, c2) = (b - g * (b - a), a + g * (b - a));
        if err(c1) < err(c2) {
            b = c2;
        } else {
            a = c1;
        }
    }
    (a + b) / 2.0
}

/// A side condition on a segment's fit ([`derive_segment_fit`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SegmentConstraint {
    /// Plain minimax: three free coefficients.
    None,
    /// f(1) = 1: f = 1 + a·(K − 1) + b·(K − 1)², two free coefficients.
    ExactAtOne,
}

/// Derivation of one segment of the piecewise normalizer: f(K) = c2·K² + c1·K + c0 minimizing
/// max |√K·f(K) − 1| over K ∈ [lo, hi] under `constraint` (Remez exchange on 20 001 points:
/// the best error equioscillates at one point more than there are free coefficients). Returns
/// (c2, c1, c0) unrounded and the max |error| on [lo, hi].
pub fn derive_segment_fit(lo: f64, hi: f64, constraint: SegmentConstraint) -> (Coeffs, f64) {
    const N: usize = 20_001;
    let ks: Vec<f64> = (0..N)
        .map(|i| lo + (hi - lo) * i as f64 / (N - 1) as f64)
        .collect();
    let points = match constraint {
        SegmentConstraint::None => 4,
        _ => 3,
    };
    // Each free coefficient's term in √K·f(K), and the fixed part of √K·f(K).
    let terms = |k: f64| -> (Vec<f64>, f64) {
        let s = k.sqrt();
        match constraint {
            SegmentConstraint::None => (vec![s * k * k, s * k, s], 0.0),
            SegmentConstraint::ExactAtOne => {
                let u = k - 1.0;
                (vec![s * u, s * u * u], s)
            }
        }
    };
    let coeffs_of = |x: &[f64]| -> Coeffs {
        match constraint {
            SegmentConstraint::None => [x[0], x[1], x[2]],
            SegmentConstraint::ExactAtOne => [x[1], x[0] - 2.0 * x[1], 1.0 - x[0] + x[1]],
        }
    };
    let err = |c: Coeffs, k: f64| k.sqrt() * normalizer::scale(k, c) - 1.0;
    let mut refs: Vec<f64> = (0..points)
        .map(|i| lo + (hi - lo) * i as f64 / (points - 1) as f64)
        .collect();
    let mut best = ([0.0; 3], f64::INFINITY);
    for _ in 0..50 {
        // The error at each reference point is ±E, alternating: Σ x_j·term_j − (±E) = 1 − fixed.
        let rows: Vec<(Vec<f64>, f64)> = refs
            .iter()
            .enumerate()
            .map(|(i, &k)| {
                let (mut row, fixed) = terms(k);
                row.push(if i % 2 == 0 { -1.0 } else { 1.0 });
                (row, 1.0 - fixed)
            })
            .collect();
        let Some(x) = solve_rows(&rows) else { break };
        let c = coeffs_of(&x);
        let e: Vec<f64> = ks.iter().map(|&k| err(c, k)).collect();
        let max = e.iter().fold(0f64, |a, v| a.max(v.abs()));
        if max < best.1 {
            best = (c, max);
        }
        // The new reference: the local extrema of |e|, the largest of each run of one sign,
        // the weaker end dropped while there are too many.
        let mut ext: Vec<(f64, f64)> = Vec::new();
        for i in 0..N {
            let v = e[i];
            let is_ext =
                i == 0 || i == N - 1 || (v.abs() >= e[i - 1].abs() && v.abs() >= e[i + 1].abs());
            if !is_ext {
                continue;
            }
            match ext.last_mut() {
                Some(last) if last.1.signum() == v.signum() => {
                    if v.abs() > last.1.abs() {
                        *last = (ks[i], v);
                    }
                }
                _ => ext.push((ks[i], v)),
            }
        }
        while ext.len() > points {
            if ext[0].1.abs() < ext[ext.len() - 1].1.abs() {
                ext.remove(0);
            } else {
                ext.pop();
            }
        }
        if ext.len() < points {
            break;
        }
        let next: Vec<f64> = ext.iter().map(|p| p.0).collect();
        if next == refs {
            break;
        }
        refs = next;
    }
    best
}

/// [`crate::linalg::solve`] for the 3 or 4 unknowns of a segment's Remez system.
fn solve_rows(rows: &[(Vec<f64>, f64)]) -> Option<Vec<f64>> {
    fn fixed<const N: usize>(rows: &[(Vec<f64>, f64)]) -> Option<Vec<f64>> {
        let m: [[f64; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| rows[i].0[j]));
        let r: [f64; N] = std::array::from_fn(|i| rows[i].1);
        crate::linalg::solve(m, r).map(|x| x.to_vec())
    }
    match rows.len() {
        3 => fixed::<3>(rows),
        4 => fixed::<4>(rows),
        n => unreachable!("a segment's system has 3 or 4 unknowns, not {n}"),
    }
}

/// Derivation of [`normalizer::PIECEWISE`]: per segment ([`normalizer::Scale::segment_range`])
/// the minimax quadratic ([`derive_segment_fit`]), segment 3 exact at K = 1; moved to the
/// segment's base (`normalizer::PIECEWISE_BASES`; see [`normalizer::Segment`]) and rounded as
/// the hardware holds them: c2 to 2⁻¹⁵, c1 and c0 to 2⁻²⁸ (segment 3's c1 to 2⁻²⁵ and its c0
/// then 1 − (c2 + c1)·(1 − base), exact, so that f(1) = 1 holds exactly). Returns the words:
/// c2 in units of 2⁻¹⁵, c1 and c0 in units of 2⁻²⁸.
pub fn derive_piecewise() -> [[f64; 3]; normalizer::SEGMENTS] {
    std::array::from_fn(|s| {
        let (lo, hi) = normalizer::Scale::segment_range(s);
        let constraint = if s == 3 {
            SegmentConstraint::ExactAtOne
        } else {
            SegmentConstraint::None
        };
        let [c2, c1, c0] = derive_segment_fit(lo, hi, constraint).0;
        let base = normalizer::PIECEWISE_BASES[s];
        // (c2·K + c1')·(K − base) + c0' = c2·K² + c1·K + c0.
        let c1b = c1 + c2 * base;
        let c0b = c0 + c1b * base;
        let c2w = (c2 * 32768.0).round();
        if s == 3 {
            let c1w = (c1b * 2f64.powi(25)).round() * 8.0;
            let c0 = 1.0 - (c2w / 32768.0 + c1w / 268435456.0) * (1.0 - base);
            [c2w, c1w, c0 * 268435456.0]
        } else {
            [
                c2w,
                (c1b * 268435456.0).round(),
                (c0b * 268435456.0).round(),
            ]
        }
    })
}

/// Round to 14 fractional bits (how the fitted constants are stored).
pub fn round_q14(c: f64) -> f64 {
    (c * 16384.0).round() / 16384.0
}

/// Max absolute error of `approx` against cos^n γ in the centre (cos^n γ ≥ 1/2) and the
/// fall-off (cos^n γ < 1/2, γ ≤ 90°). Returns (centre, fall-off) with γ in radians.
pub fn highlight_errors(n: u32, approx: impl Fn(f64) -> f64) -> (Extremum, Extremum) {
    let gamma_half = 0.5f64.powf(1.0 / n as f64).acos();
    let err = |g: f64| approx(g.cos()) - brdf::cos_pow(n, g.cos());
    let centre = max_abs(err, 0.0, gamma_half);
    let falloff = max_abs(err, gamma_half, std::f64::consts::FRAC_PI_2);
    (centre, falloff)
}

/// Kind of figure in an [`Entry`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Metric {
    /// Max |relative error| over the domain (a fraction: 0.0035 = 0.35%).
    MaxRelative,
    /// Max |absolute error| (relative to a peak value of 1).
    MaxAbsolute,
    /// A constant's relative error.
    Relative,
    /// A ratio of two errors (how many times smaller).
    Ratio,
    /// A plain value (e.g. f(1) − 1).
    Value,
}

/// One line of the accuracy report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Entry {
    /// Stable identifier, e.g. `normalizer-published`.
    pub id: String,
    /// What is approximated, by what.
    pub what: String,
    /// The domain the figure is measured on.
    pub domain: String,
    pub metric: Metric,
    /// The measured figure (signed where the sign means something; compare |measured|).
    pub measured: f64,
    /// Where the extremum lies (domain variable), if the figure is an extremum.
    pub at: Option<f64>,
    /// The sources' figure, same units, if they state one.
    pub claim: Option<f64>,
    /// Where the claim comes from.
    pub source: Option<String>,
}

/// The full report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    pub entries: Vec<Entry>,
}

impl Report {
    pub fn get(&self, id: &str) -> Option<&Entry> {
        self.entries.iter().find(|e| e.id == id)
    }
}

fn entry(id: &str, what: &str, domain: &str, metric: Metric, measured: f64) -> Entry {
    Entry {
        id: id.into(),
        what: what.into(),
        domain: domain.into(),
        metric,
        measured,
        at: None,
        claim: None,
        source: None,
    }
}

impl Entry {
    fn at(mut self, x: f64) -> Entry {
        self.at = Some(x);
        self
    }
    fn claim(mut self, c: f64, source: &str) -> Entry {
        self.claim = Some(c);
        self.source = Some(source.into());
        self
    }
    /// [`Entry::claim`] where the sources state one.
    fn claimed(self, claim: Option<(f64, &str)>) -> Entry {
        match claim {
            Some((c, source)) => self.claim(c, source),
            None => self,
        }
    }
    fn ext(id: &str, what: &str, domain: &str, metric: Metric, e: Extremum) -> Entry {
        entry(id, what, domain, metric, e.value).at(e.at)
    }
}

/// The W variants reported: (id suffix, label, k, shift-add division).
fn w_variants() -> Vec<(String, String, u32, bool)> {
    let mut v = Vec::new();
    for k in brdf::KS {
        v.push((
            format!("w-k{k}"),
            format!("W(n,γ) k={k}, shift-add 1/{}", k + 1),
            k,
            true,
        ));
        v.push((
            format!("w-k{k}-exact"),
            format!("W(n,γ) k={k}, exact 1/{}", k + 1),
            k,
            false,
        ));
    }
    v
}

/// A quadratic form reported: (id, what, coefficients, the sources' claim if any).
type Form = (&'static str, String, Coeffs, Option<(f64, &'static str)>);

/// The normalizer's f(K) forms.
fn normalizer_forms() -> [Form; 2] {
    [
        (
            "normalizer-published",
            "normalizer f(K) = 0.822K² − 2.046K + 2.227 ≈ 1/√K".into(),
            normalizer::PUBLISHED,
            Some((0.0036, "seed 000, formula (1): 0.36%")),
        ),
        (
            "normalizer-fit",
            format!(
                "normalizer-fit f(K) = 1 − (K−1)/2 + c(K−1)², c = {:.6}",
                normalizer::FIT_C
            ),
            normalizer::FIT,
            None,
        ),
    ]
}

/// The fast method's 1/√(M+1) forms.
fn inv_sqrt_forms() -> [Form; 4] {
    [
        (
            "inv-sqrt-chebyshev",
            "1/√(M+1) ≈ 1.003 − 0.403M + 0.82M² (Chebyshev)".into(),
            fast::CHEBYSHEV,
            Some((0.00357, "seed 001 §3.1: 0.357%")),
        ),
        (
            "inv-sqrt-shift-add",
            "1/√(M+1) ≈ 1 − lM + 2lM², l = 1/4+1/8+1/32".into(),
            fast::SHIFT_ADD,
            Some((0.0051, "seed 001 §3.1: 0.51%")),
        ),
        (
            "inv-sqrt-taylor",
            "1/√(M+1) ≈ 1 − M/2 + 3M²/8 (Taylor)".into(),
            fast::TAYLOR,
            Some((0.0498, "seed 001 §3.1: 4.98%")),
        ),
        (
            "inv-sqrt-fit",
            format!(
                "1/√(M+1) ≈ 1 − M/2 + cM², c = {:.6} (fast-fit)",
                fast::FIT_C
            ),
            fast::FIT,
            None,
        ),
    ]
}

/// Measure everything. Takes about a second in release builds.
pub fn report() -> Report {
    use Metric::*;
    let mut e = Vec::new();
    let kd = "K ∈ [0.499, 1]";
    let md = "M ∈ [−0.5, 0]";

    for (id, what, c, claim) in normalizer_forms() {
        e.push(Entry::ext(id, &what, kd, MaxRelative, normalizer_max(c)).claimed(claim));
    }
    let pw = normalizer::PIECEWISE;
    let (lo, hi) = normalizer::K_DOMAIN;
    e.push(Entry::ext(
        "normalizer-pw",
        "normalizer-pw f(K) by four segments of K (bases 3/8, 5/8, 3/4, 7/8)",
        kd,
        MaxRelative,
        max_abs(|k| k.sqrt() * pw.at(k) - 1.0, lo, hi),
    ));
    for (id, what, c) in [
        (
            "normalizer-published-bias",
            "normalizer published f(1) − 1 (bias where fine meshes live)",
            normalizer::PUBLISHED.into(),
        ),
        (
            "normalizer-fit-bias",
            "normalizer-fit f(1) − 1",
            normalizer::FIT.into(),
        ),
        (
            "normalizer-pw-bias",
            "normalizer-pw f(1) − 1",
            normalizer::PIECEWISE,
        ),
    ] {
        e.push(entry(id, what, "K = 1", Value, c.at(1.0) - 1.0));
    }
    for (id, what, c, claim) in inv_sqrt_forms() {
        e.push(Entry::ext(id, &what, md, MaxRelative, inv_sqrt_max(c)).claimed(claim));
    }
    e.push(entry(
        "inv-sqrt-chebyshev-bias",
        "Chebyshev f(0) − 1 (bias where fine meshes live)",
        "M = 0",
        Value,
        normalizer::scale(0.0, fast::CHEBYSHEV) - 1.0,
    ));
    e.push(
        entry(
            "one-third",
            "1/3 ≈ 1/2 − 1/8 − 1/32 − 1/128",
            "constant",
            Relative,
            (cubic::THIRD - 1.0 / 3.0) * 3.0,
        )
        .claim(0.0079, "seed 001 §2.2: does not exceed 0.79%"),
    );
    for k in brdf::KS {
        let exact = 1.0 / (k as f64 + 1.0);
        let approx = brdf::recip_shift_add(k).expect("k in KS");
        e.push(entry(
            &format!("div-k{k}"),
            &format!("(n+1)/{} by shifts and adds", k + 1),
            "constant",
            Relative,
            (approx - exact) / exact,
        ));
    }
    // W(n, γ) and Schlick against cos^n γ, in the centre and the fall-off.
    for n in [50u32, 1000] {
        let domains = [
            ("centre", format!("n = {n}, cos^n γ ≥ 1/2 (centre)")),
            ("falloff", format!("n = {n}, cos^n γ < 1/2 (fall-off)")),
        ];
        let mut push_pair = |id: &str, label: &str, errors: [Extremum; 2]| {
            for ((part, domain), err) in domains.iter().zip(errors) {
                let id = format!("{id}-n{n}-{part}");
                e.push(Entry::ext(&id, label, domain, MaxAbsolute, err));
            }
        };
        let mut w16 = None;
        for (id, label, k, shift) in w_variants() {
            let a = brdf::slope(n, k, shift);
            let (c, f) = highlight_errors(n, |x| brdf::w_kernel(a, k, x));
            push_pair(&id, &label, [c, f]);
            if k == 16 && shift {
                w16 = Some([c, f]);
            }
        }
        let (sc, sf) = highlight_errors(n, |c| brdf::schlick(n, c));
        push_pair("schlick", "Schlick c/(n − nc + c)", [sc, sf]);
        let w16 = w16.expect("k = 16 is among the variants");
        let ratios = [
            (
                "centre",
                sc,
                7.0,
                "seed 000: 7× lower max error at the highlight centre",
            ),
            (
                "fall-off",
                sf,
                13.0,
                "seed 000: 13× lower in the fall-off (blooming)",
            ),
        ];
        for (((part, domain), (what, schlick, claim, source)), w) in
            domains.iter().zip(ratios).zip(w16)
        {
            e.push(
                entry(
                    &format!("schlick-over-w-k16-n{n}-{part}"),
                    &format!("Schlick error ÷ W k=16 (shift-add) error, {what}"),
                    domain,
                    Ratio,
                    schlick.value.abs() / w.value.abs(),
                )
                .claim(claim, source),
            );
        }
    }
    Report { entries: e }
}

/// One plotted error curve.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

/// One plot: several curves over a common x axis.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Plot {
    /// File stem, e.g. `normalizer`.
    pub id: String,
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
}

fn sampled(name: &str, lo: f64, hi: f64, n: usize, f: impl Fn(f64) -> f64) -> Series {
    let points = (0..n)
        .map(|i| {
            let x = lo + (hi - lo) * i as f64 / (n - 1) as f64;
            (x, f(x))
        })
        .collect();
    Series {
        name: name.into(),
        points,
    }
}

/// A plot of the relative error in percent of each named form over `domain`, at 501 points.
fn percent_plot(
    (id, title, x_label): (&str, &str, &str),
    (lo, hi): (f64, f64),
    forms: &[(&str, Coeffs)],
    error: fn(Coeffs, f64) -> f64,
) -> Plot {
    let series = forms
        .iter()
        .map(|&(name, c)| sampled(name, lo, hi, 501, |x| 100.0 * error(c, x)))
        .collect();
    plot(id.into(), title.into(), x_label, "error, %", series)
}

fn plot(id: String, title: String, x_label: &str, y_label: &str, series: Vec<Series>) -> Plot {
    Plot {
        id,
        title,
        x_label: x_label.into(),
        y_label: y_label.into(),
        series,
    }
}

/// The error curves behind the report, for plotting (errors in percent).
pub fn plots() -> Vec<Plot> {
    use fast::{CHEBYSHEV, FIT, SHIFT_ADD, TAYLOR};
    let inv_sqrt = |labels, forms: &[(&str, Coeffs)]| {
        percent_plot(labels, fast::M_DOMAIN, forms, inv_sqrt_error)
    };
    let normalizer_labels = ("normalizer", "Normalizer: relative error of |N·f(K)|", "K");
    let normalizer_forms = [
        ("published", normalizer::PUBLISHED),
        ("fit", normalizer::FIT),
    ];
    let mut out = vec![
        percent_plot(
            normalizer_labels,
            normalizer::K_DOMAIN,
            &normalizer_forms,
            normalizer_error,
        ),
        inv_sqrt(
            ("inv-sqrt", "1/sqrt(M+1): relative error", "M"),
            &[
                ("Chebyshev", CHEBYSHEV),
                ("shift-add", SHIFT_ADD),
                ("fit", FIT),
            ],
        ),
        inv_sqrt(
            ("inv-sqrt-taylor", "1/sqrt(M+1): Taylor vs Chebyshev", "M"),
            &[("Taylor", TAYLOR), ("Chebyshev", CHEBYSHEV)],
        ),
    ];
    for n in [50u32, 1000] {
        let hi = (0.01f64).powf(1.0 / n as f64).acos().to_degrees() * 1.3;
        let minus_cos_pow = |name: &str, approx: &dyn Fn(f64) -> f64| {
            sampled(name, 0.0, hi, 801, |g| {
                let c = g.to_radians().cos();
                approx(c) - brdf::cos_pow(n, c)
            })
        };
        let mut series = Vec::new();
        for k in brdf::KS {
            let a = brdf::slope(n, k, true);
            series.push(minus_cos_pow(&format!("W k={k}"), &|c| {
                brdf::w_kernel(a, k, c)
            }));
        }
        series.push(minus_cos_pow("Schlick", &|c| brdf::schlick(n, c)));
        out.push(plot(
            format!("brdf-n{n}"),
            format!("Specular approximations minus cos^n, n = {n}"),
            "angle, degrees",
            "absolute error",
            series,
        ));
    }
    out
}
