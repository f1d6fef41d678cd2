//! Points, vectors, headings and turn angles.
//!
//! World frame as in ROS: x to the right, y up, metres. Headings of the thesis genome are in
//! degrees measured from +x (003 §3.2); rotation time is computed in radians (R7).

/// A position in metres in the world frame.
pub type Point = nalgebra::Point2<f64>;
/// A displacement in metres.
pub type Vector = nalgebra::Vector2<f64>;

/// Segments shorter than this (metres) are degenerate: they have no heading (R6, R18).
pub const ZERO_LENGTH: f64 = 1e-9;

/// Unit direction of a heading given in degrees (003 eq. 3.7).
pub fn direction_deg(alpha_deg: f64) -> Vector {
    let rad = alpha_deg.to_radians();
    Vector::new(rad.cos(), rad.sin())
}

/// Heading `β(V)` of a vector in degrees, in (-180, 180] (003 §3.1.2, used by eq. 3.2).
pub fn heading_deg(v: Vector) -> f64 {
    v.y.atan2(v.x).to_degrees()
}

/// `rotAngle(d)` of 003 eq. 3.2: wraps a heading difference into [-180, 180] degrees.
pub fn rot_angle(d: f64) -> f64 {
    if d > 180.0 {
        d - 360.0
    } else if d < -180.0 {
        d + 360.0
    } else {
        d
    }
}

/// Signed turn in degrees between two consecutive segment vectors (003 eq. 3.2:
/// `α_i = rotAngle(β(V_i) − β(V_{i+1}))`).
pub fn turn_deg(from: Vector, to: Vector) -> f64 {
    rot_angle(heading_deg(from) - heading_deg(to))
}

/// Normalises an angle in degrees into [0, 360).
pub fn normalise_deg(alpha: f64) -> f64 {
    let a = alpha.rem_euclid(360.0);
    // rem_euclid can return exactly 360.0 for tiny negative inputs.
    if a >= 360.0 { 0.0 } else { a }
}

/// `polar(v)` of thesis-ga §2.2: the move `(alpha_deg in [0,360), dist_m)` reproducing `v`.
/// A (near) zero vector keeps `previous_alpha` and gets distance 0.
pub fn polar_deg(v: Vector, previous_alpha: f64) -> (f64, f64) {
    let dist = v.norm();
    if dist < ZERO_LENGTH { (previous_alpha, 0.0) } else { (normalise_deg(heading_deg(v)), dist) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rot_angle_wraps_into_half_turns() {
        for (d, expected) in
            [(0.0, 0.0), (190.0, -170.0), (-190.0, 170.0), (180.0, 180.0), (-180.0, -180.0), (350.0, -10.0)]
        {
            assert!((rot_angle(d) - expected).abs() < 1e-12, "{d}");
        }
    }

    #[test]
    fn turn_between_axis_vectors() {
        let east = Vector::new(1.0, 0.0);
        let north = Vector::new(0.0, 1.0);
        let west = Vector::new(-1.0, 0.0);
        assert!((turn_deg(east, north).abs() - 90.0).abs() < 1e-12);
        assert!((turn_deg(east, west).abs() - 180.0).abs() < 1e-12);
        assert!(turn_deg(east, east).abs() < 1e-12);
    }

    #[test]
    fn polar_round_trips_direction() {
        let v = Vector::new(-3.0, -4.0);
        let (alpha, dist) = polar_deg(v, 7.0);
        assert!((dist - 5.0).abs() < 1e-12);
        assert!((0.0..360.0).contains(&alpha));
        let back = direction_deg(alpha) * dist;
        assert!((back - v).norm() < 1e-9);
        assert_eq!(polar_deg(Vector::zeros(), 7.0), (7.0, 0.0));
    }

    #[test]
    fn normalise_stays_in_range() {
        assert_eq!(normalise_deg(-1e-20), 0.0);
        assert!((normalise_deg(-90.0) - 270.0).abs() < 1e-12);
        assert!((normalise_deg(725.0) - 5.0).abs() < 1e-12);
    }
}
