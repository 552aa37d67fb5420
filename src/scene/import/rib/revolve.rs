//! `Paraboloid` and `Hyperboloid` as exact rational surfaces of revolution (NURBS): the
//! profile — a quadratic Bézier parabola, a straight line — swept about z by the rational
//! quadratic circle, split into arcs of at most 90°. The surface is tessellated like every
//! other NURBS; its parameters are RenderMan's (u around from angle 0 to `thetamax`, v along
//! the profile).

use crate::scene::desc::{MeshDesc, V3};

/// Control points `(cos, sin, weight)` of the unit circular arc from 0 to `theta` radians
/// (0 < θ ≤ 2π) and its knot vector (degree 2).
fn arc(theta: f64) -> (Vec<(f64, f64, f64)>, Vec<f64>) {
    let n = (theta / std::f64::consts::FRAC_PI_2 - 1e-9).ceil().max(1.0) as usize;
    let d = theta / n as f64;
    let w = (d / 2.0).cos();
    let mut pts = Vec::with_capacity(2 * n + 1);
    for k in 0..n {
        let a = k as f64 * d;
        let m = a + d / 2.0;
        pts.push((a.cos(), a.sin(), 1.0));
        pts.push((m.cos() / w, m.sin() / w, w));
    }
    pts.push((theta.cos(), theta.sin(), 1.0));
    let mut knots = vec![0.0; 3];
    for k in 1..n {
        let t = k as f64 / n as f64;
        knots.extend([t, t]);
    }
    knots.extend([1.0; 3]);
    (pts, knots)
}

/// The surface swept by the profile whose control points are `(radius, z)` of a Bézier
/// curve of degree `profile.len() − 1`, through `theta_max` degrees.
fn revolve(profile: &[(f64, f64)], theta_max: f64) -> MeshDesc {
    let theta = theta_max.to_radians().clamp(1e-6, std::f64::consts::TAU);
    let (circle, knots_u) = arc(theta);
    let degree_v = profile.len() as u32 - 1;
    let mut knots_v = vec![0.0; profile.len()];
    knots_v.extend(vec![1.0; profile.len()]);
    let mut points = Vec::with_capacity(circle.len() * profile.len());
    for &(r, z) in profile {
        for &(c, s, w) in &circle {
            points.push((r * c, r * s, z, w));
        }
    }
    MeshDesc::Nurbs {
        degree_u: 2,
        degree_v,
        count_u: circle.len() as u32,
        count_v: profile.len() as u32,
        knots_u,
        knots_v,
        points,
        variables: Default::default(),
    }
}

/// `Paraboloid rmax zmin zmax thetamax`: `z = zmax·(r/rmax)²` for `z ∈ [zmin, zmax]`.
/// An error (the reason) when the values describe no surface.
pub fn paraboloid(rmax: f64, zmin: f64, zmax: f64, theta_max: f64) -> Result<MeshDesc, String> {
    let ok = rmax > 0.0 && zmax > 0.0 && zmin >= 0.0 && zmin < zmax && theta_max > 0.0;
    if !(ok && [rmax, zmin, zmax, theta_max].iter().all(|x| x.is_finite())) {
        return Err(format!(
            "Paraboloid needs rmax > 0, 0 ≤ zmin < zmax and thetamax > 0, found \
             {rmax} {zmin} {zmax} {theta_max}"
        ));
    }
    // r(z) = rmax·√(z/zmax); in r the profile z = zmax·r²/rmax² is a parabola, whose
    // quadratic Bézier between r0 and r1 has its middle point where the end tangents meet.
    let (r0, r1) = (rmax * (zmin / zmax).sqrt(), rmax);
    let k = zmax / (rmax * rmax);
    let profile = [
        (r0, k * r0 * r0),
        ((r0 + r1) / 2.0, k * r0 * r1),
        (r1, zmax),
    ];
    Ok(revolve(&profile, theta_max))
}

/// `Hyperboloid point1 point2 thetamax`: the line from `point1` to `point2` swept about z.
pub fn hyperboloid(p1: V3, p2: V3, theta_max: f64) -> Result<MeshDesc, String> {
    let finite = [p1.0, p1.1, p1.2, p2.0, p2.1, p2.2, theta_max]
        .iter()
        .all(|x| x.is_finite());
    if !(finite && theta_max > 0.0) || p1 == p2 {
        return Err(format!(
            "Hyperboloid needs two different points and thetamax > 0, found {p1:?} {p2:?} \
             {theta_max}"
        ));
    }
    // Each point of the line turns rigidly about z: the arc's control points (cos, sin)
    // scaled as the arc's rotate the point (x, y) from its own angle.
    let (circle, knots_u) = arc(theta_max.to_radians().clamp(1e-6, std::f64::consts::TAU));
    let mut points = Vec::with_capacity(2 * circle.len());
    for p in [p1, p2] {
        for &(c, s, w) in &circle {
            // R(a)·(x, y) with the arc's (cos a, sin a) scaled as the arc's control point.
            points.push((p.0 * c - p.1 * s, p.0 * s + p.1 * c, p.2, w));
        }
    }
    Ok(MeshDesc::Nurbs {
        degree_u: 2,
        degree_v: 1,
        count_u: circle.len() as u32,
        count_v: 2,
        knots_u,
        knots_v: vec![0.0, 0.0, 1.0, 1.0],
        points,
        variables: Default::default(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The point of a NURBS description at `(u, v)` by de Boor's definition (Cox–de Boor
    /// basis functions, rational).
    fn eval(mesh: &MeshDesc, u: f64, v: f64) -> (f64, f64, f64) {
        let MeshDesc::Nurbs {
            degree_u,
            degree_v,
            count_u,
            count_v,
            knots_u,
            knots_v,
            points,
            ..
        } = mesh
        else {
            panic!("{mesh:?}")
        };
        fn basis(i: usize, p: usize, t: f64, k: &[f64]) -> f64 {
            if p == 0 {
                let last = t >= k[k.len() - 1] && k[i + 1] >= k[k.len() - 1] && k[i] < k[i + 1];
                return if (k[i] <= t && t < k[i + 1]) || last {
                    1.0
                } else {
                    0.0
                };
            }
            let a = if k[i + p] > k[i] {
                (t - k[i]) / (k[i + p] - k[i]) * basis(i, p - 1, t, k)
            } else {
                0.0
            };
            let b = if k[i + p + 1] > k[i + 1] {
                (k[i + p + 1] - t) / (k[i + p + 1] - k[i + 1]) * basis(i + 1, p - 1, t, k)
            } else {
                0.0
            };
            a + b
        }
        let (mut x, mut y, mut z, mut w) = (0.0, 0.0, 0.0, 0.0);
        for j in 0..*count_v as usize {
            for i in 0..*count_u as usize {
                let b = basis(i, *degree_u as usize, u, knots_u)
                    * basis(j, *degree_v as usize, v, knots_v);
                let p = points[j * *count_u as usize + i];
                x += b * p.0 * p.3;
                y += b * p.1 * p.3;
                z += b * p.2 * p.3;
                w += b * p.3;
            }
        }
        (x / w, y / w, z / w)
    }

    #[test]
    fn paraboloid_points_lie_on_the_paraboloid() {
        let m = paraboloid(2.0, 0.5, 3.0, 270.0).unwrap();
        for i in 0..=10 {
            for j in 0..=10 {
                let (x, y, z) = eval(&m, i as f64 / 10.0, j as f64 / 10.0);
                let r2 = x * x + y * y;
                assert!((z - 3.0 * r2 / 4.0).abs() < 1e-12, "({x}, {y}, {z})");
                assert!((0.5 - 1e-12..=3.0 + 1e-12).contains(&z));
                // Angles sweep 0…270°.
                let a = y.atan2(x).rem_euclid(std::f64::consts::TAU).to_degrees();
                assert!(r2 < 1e-12 || a <= 270.0 + 1e-9 || a >= 360.0 - 1e-9, "{a}");
            }
        }
        let (x, y, z) = eval(&m, 0.0, 1.0);
        assert!((x - 2.0).abs() < 1e-12 && y.abs() < 1e-12 && (z - 3.0).abs() < 1e-12);
    }

    #[test]
    fn hyperboloid_is_the_swept_line() {
        let (p1, p2) = ((1.0, 0.0, -1.0), (0.0, 1.0, 1.0));
        let m = hyperboloid(p1, p2, 360.0).unwrap();
        for i in 0..=12 {
            for j in 0..=4 {
                let (u, v) = (i as f64 / 12.0, j as f64 / 4.0);
                let (x, y, z) = eval(&m, u, v);
                // The point of the line at v, rotated about z: its radius and height match.
                let q = (1.0 - v, v, -1.0 + 2.0 * v);
                let r_line: f64 = (q.0 * q.0 + q.1 * q.1).sqrt();
                assert!(((x * x + y * y).sqrt() - r_line).abs() < 1e-12, "{u} {v}");
                assert!((z - q.2).abs() < 1e-12);
            }
        }
        // u = 0 is the line itself.
        let (x, y, z) = eval(&m, 0.0, 0.5);
        assert!((x - 0.5).abs() < 1e-12 && (y - 0.5).abs() < 1e-12 && z.abs() < 1e-12);
    }
}
