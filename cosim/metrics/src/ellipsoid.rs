//! The 95 % ellipsoid of a load's point cloud (thesis §7.2.2, Figs. 7.4/7.5): the volume the load
//! stays in for 95 % of the test period. Positions in metres, in whatever frame the points are
//! given (world frame W, or relative to the set-point for variable set-points, §7.4).

use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// An ellipsoid {c + Σ uₖ·vₖ : Σ (uₖ/sₖ)² ≤ 1} with centre c, principal directions vₖ and
/// semi-axes sₖ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    /// The point cloud's mean (m).
    pub center: [f64; 3],
    /// Unit principal directions (each of either sign), by decreasing semi-axis, orthogonal.
    pub axes: [[f64; 3]; 3],
    /// Semi-axes along `axes` (m); 0 along a direction in which the cloud has no spread.
    pub semi_axes: [f64; 3],
    /// 4/3·π·s₁s₂s₃ (m³).
    pub volume: f64,
}

/// A principal standard deviation below this share of the largest counts as zero spread: the
/// eigen-solver's rounding (~1e-16 of the largest variance) leaves a flat direction ~1e-8 of the
/// largest standard deviation; real spreads are far larger.
const FLAT: f64 = 1e-6;
/// ...and one below this share of the coordinates' magnitude: the rounding of the mean alone
/// gives identical points a spread of ~1e-17 of their coordinates.
const ROUNDING: f64 = 1e-12;

/// The ellipsoid of `points` that holds the share `fraction` of them (0.95 in the thesis).
///
/// As in the thesis, its shape comes from the data and only its size is fitted: principal
/// directions are the eigenvectors of the points' covariance, semi-axes are s·σₖ with σₖ the
/// standard deviations along them, and the one scale factor s is the `fraction`-quantile of the
/// points' Mahalanobis distances dᵢ = √(Σₖ (vₖ·(pᵢ − c))²/σₖ²). Quantile rule (nearest rank): s is
/// the ⌈fraction·n⌉-th smallest dᵢ, the least s with at least fraction·n points inside. (Whether
/// the covariance divides by n or n − 1 does not matter: s absorbs it.)
///
/// A flat cloud (a σₖ below 1e-6 of the largest or below 1e-12 of the largest coordinate: points
/// on a plane, a line or all equal) has semi-axis 0 there and volume 0, never NaN; its distances
/// use only the directions with spread. (The thesis' ideal free swing, a planar arc, is of this
/// kind, §7.2.2.)
///
/// `None` for fewer than 4 points (no volume can be spanned), a non-finite coordinate, or
/// `fraction` outside (0, 1].
pub fn ellipsoid(points: &[[f64; 3]], fraction: f64) -> Option<Ellipsoid> {
    let usable = points.len() >= 4 && points.iter().flatten().all(|x| x.is_finite());
    if !(usable && fraction > 0.0 && fraction <= 1.0) {
        return None;
    }
    let cloud: Vec<Vector3<f64>> = points.iter().map(|p| Vector3::from(*p)).collect();
    let center = cloud.iter().sum::<Vector3<f64>>() / cloud.len() as f64;
    let magnitude = points.iter().flatten().fold(0.0, |m: f64, x| m.max(x.abs()));
    let (axes, sigmas) = principal_axes(&cloud, &center, ROUNDING * magnitude);
    let mut distances: Vec<f64> = cloud.iter().map(|p| mahalanobis(&(p - center), &axes, &sigmas)).collect();
    distances.sort_by(f64::total_cmp);
    let scale = distances[nearest_rank(fraction, distances.len()) - 1];
    let semi_axes = sigmas.map(|s| scale * s);
    let volume = 4.0 / 3.0 * std::f64::consts::PI * semi_axes.iter().product::<f64>();
    Some(Ellipsoid { center: center.into(), axes: axes.map(|a| a.into()), semi_axes, volume })
}

/// Principal directions and standard deviations (m) by decreasing spread; flat ones (σ below
/// FLAT·largest or `noise` m) σ = 0.
fn principal_axes(cloud: &[Vector3<f64>], center: &Vector3<f64>, noise: f64) -> ([Vector3<f64>; 3], [f64; 3]) {
    let covariance =
        cloud.iter().map(|p| (p - center) * (p - center).transpose()).sum::<Matrix3<f64>>() / (cloud.len() - 1) as f64;
    let eigen = SymmetricEigen::new(covariance);
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| eigen.eigenvalues[b].total_cmp(&eigen.eigenvalues[a]));
    let largest = eigen.eigenvalues[order[0]].max(0.0).sqrt();
    let sigma = |k: usize| {
        let s = eigen.eigenvalues[k].max(0.0).sqrt();
        if s > FLAT * largest && s > noise {
            s
        } else {
            0.0
        }
    };
    (order.map(|k| eigen.eigenvectors.column(k).into_owned()), order.map(sigma))
}

/// Mahalanobis distance of an offset from the centre, over the directions with spread.
fn mahalanobis(offset: &Vector3<f64>, axes: &[Vector3<f64>; 3], sigmas: &[f64; 3]) -> f64 {
    axes.iter().zip(sigmas).filter(|(_, &s)| s > 0.0).map(|(a, s)| (a.dot(offset) / s).powi(2)).sum::<f64>().sqrt()
}

/// ⌈fraction·n⌉ in 1..=n, forgiving the rounding of fraction·n (0.95·100 must give 95, not 96).
fn nearest_rank(fraction: f64, n: usize) -> usize {
    ((fraction * n as f64 - 1e-9).ceil() as usize).clamp(1, n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;
    use std::f64::consts::PI;

    /// The k-th point of the Halton sequence in bases 2, 3, 5: a deterministic, evenly spread
    /// sample of the unit cube.
    fn halton(k: usize) -> [f64; 3] {
        [2, 3, 5].map(|base| {
            let (mut i, mut f, mut x) = (k, 1.0, 0.0);
            while i > 0 {
                f /= base as f64;
                x += f * (i % base) as f64;
                i /= base;
            }
            x
        })
    }

    const SEMI: [f64; 3] = [0.03, 0.02, 0.01];

    /// The Halton points that fall in the unit ball, stretched to semi-axes SEMI, rotated by
    /// `rotation` and moved to `center`: a uniform filling of a known ellipsoid.
    fn filled_ellipsoid(rotation: &Rotation3<f64>, center: [f64; 3]) -> Vec<[f64; 3]> {
        (1..40_000)
            .map(|k| Vector3::from(halton(k).map(|u| 2.0 * u - 1.0)))
            .filter(|u| u.norm() <= 1.0)
            .map(|u| (rotation * u.component_mul(&Vector3::from(SEMI)) + Vector3::from(center)).into())
            .collect()
    }

    /// In a uniformly filled ball the normalised radius ρ has P(ρ ≤ r) = r³, so the 95 % ellipsoid
    /// has semi-axes 0.95^(1/3)·(a, b, c) and volume 0.95·4/3·π·abc, along the rotated axes.
    #[test]
    fn the_95_percent_ellipsoid_of_a_filled_ellipsoid() {
        let rotation = Rotation3::from_euler_angles(0.3, -0.5, 1.1);
        let center = [1.0, -2.0, 0.5];
        let points = filled_ellipsoid(&rotation, center);
        let e = ellipsoid(&points, 0.95).unwrap();
        let exact = 0.95 * 4.0 / 3.0 * PI * SEMI.iter().product::<f64>();
        // ~21 000 points: within 0.06 % in volume, 0.1 % per semi-axis, axes to 1e-7.
        assert!((e.volume / exact - 1.0).abs() < 0.005, "{} vs {exact}", e.volume);
        for k in 0..3 {
            let expected = 0.95f64.cbrt() * SEMI[k];
            assert!((e.semi_axes[k] / expected - 1.0).abs() < 0.005, "axis {k}: {}", e.semi_axes[k]);
            let alignment = Vector3::from(e.axes[k]).dot(&rotation.matrix().column(k));
            assert!(alignment.abs() > 1.0 - 1e-5, "axis {k}: {alignment}");
            assert!((e.center[k] - center[k]).abs() < 1e-4);
        }
        assert!((e.volume - 4.0 / 3.0 * PI * e.semi_axes.iter().product::<f64>()).abs() < 1e-18);
    }

    /// The nearest-rank rule: exactly ⌈0.95·n⌉ points lie in the ellipsoid (ties aside), and a
    /// 0.1 % smaller one holds fewer than 95 %.
    #[test]
    fn the_scale_leaves_the_requested_share_inside() {
        let points = filled_ellipsoid(&Rotation3::from_euler_angles(0.7, 0.2, -0.4), [0.0; 3]);
        let e = ellipsoid(&points, 0.95).unwrap();
        let inside = |shrink: f64| {
            let level = |p: &[f64; 3]| -> f64 {
                let d = Vector3::from(*p) - Vector3::from(e.center);
                (0..3).map(|k| (Vector3::from(e.axes[k]).dot(&d) / (shrink * e.semi_axes[k])).powi(2)).sum()
            };
            points.iter().filter(|p| level(p) <= 1.0 + 1e-12).count()
        };
        let n = points.len();
        assert_eq!(inside(1.0), (0.95 * n as f64).ceil() as usize, "n = {n}");
        assert!((inside(0.999) as f64) < 0.95 * n as f64);
    }

    #[test]
    fn flat_clouds_have_zero_volume() {
        let line: Vec<[f64; 3]> = (0..50).map(|k| [0.1 * k as f64, 0.2 * k as f64 - 1.0, -0.05 * k as f64]).collect();
        let e = ellipsoid(&line, 0.95).unwrap();
        assert_eq!(e.volume, 0.0);
        assert_eq!(e.semi_axes[1..], [0.0, 0.0]);
        // Along the line the points are uniform: the 48th of 50 distances from the middle.
        let length = (0.1f64.powi(2) + 0.2f64.powi(2) + 0.05f64.powi(2)).sqrt();
        assert!((e.semi_axes[0] - 23.5 * length).abs() < 1e-9, "{}", e.semi_axes[0]);
        // The mean of six 0.1 is 0.09999999999999999: a spread of 1e-17 that must count as none.
        let same = ellipsoid(&[[0.3, 0.1, 2.0]; 6], 0.95).unwrap();
        assert_eq!((same.volume, same.semi_axes), (0.0, [0.0; 3]));
        assert!((0..3).all(|k| (same.center[k] - [0.3, 0.1, 2.0][k]).abs() < 1e-15));
        let plane: Vec<[f64; 3]> = (0..40).map(|k| [(k % 7) as f64, (k / 7) as f64, 3.0]).collect();
        let flat = ellipsoid(&plane, 0.95).unwrap();
        assert!(flat.volume == 0.0 && flat.semi_axes[0] > 0.0 && flat.semi_axes[1] > 0.0);
    }

    #[test]
    fn too_few_or_unusable_points() {
        let three = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert_eq!(ellipsoid(&three, 0.95), None);
        let four = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!(ellipsoid(&four, 0.95).unwrap().volume > 0.0);
        assert_eq!(ellipsoid(&four, 0.0), None);
        assert_eq!(ellipsoid(&four, 1.5), None);
        assert_eq!(ellipsoid(&[[f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], 0.95), None);
    }
}
