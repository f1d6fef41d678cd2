//! Path length (003 eq. 3.1), turning (eq. 3.2) and rotation time (eq. 3.3 as resolved by
//! R6–R7).

use crate::geom::{Point, Vector, ZERO_LENGTH};

/// `PA_len`: the sum of segment lengths in metres (003 eq. 3.1).
pub fn path_length(points: &[Point]) -> f64 {
    points.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
}

/// Turning along a path: the sum of absolute turn angles in radians between consecutive
/// non-degenerate segments (003 eq. 3.2; zero-length segments carry the heading over, R6) and
/// the number of non-zero turns.
pub fn turning(points: &[Point]) -> (f64, usize) {
    let mut previous = None;
    let mut total_deg = 0.0;
    let mut turns = 0;
    for w in points.windows(2) {
        let v = w[1] - w[0];
        if v.norm() < ZERO_LENGTH {
            continue;
        }
        if let Some(prev) = previous {
            let a = abs_turn_deg(prev, v);
            if a > 1e-9 {
                turns += 1;
            }
            total_deg += a;
        }
        previous = Some(v);
    }
    (total_deg.to_radians(), turns)
}

/// `|α|` of 003 eq. 3.2 in degrees: the unsigned angle between two segment vectors, which is
/// `|rotAngle(β(V_i) − β(V_{i+1}))|` computed with one `atan2` instead of two.
pub fn abs_turn_deg(from: Vector, to: Vector) -> f64 {
    let cross = from.x * to.y - from.y * to.x;
    cross.abs().atan2(from.dot(&to)).to_degrees()
}

/// `T_rot` in seconds: total absolute turn (rad) over the rotation speed `R_rot` (rad/s);
/// 0 when `R_rot` = 0 disables the rotation cost (003 eq. 3.3, R6–R7).
pub fn rotation_time(total_turn_rad: f64, r_rot: f64) -> f64 {
    if r_rot > 0.0 { total_turn_rad / r_rot } else { 0.0 }
}

/// The time model of 003 eqs. 3.1–3.3: `length_m` at `speed` plus `turn_rad` at `rot_speed`
/// (free when `rot_speed` is 0). Every path time in covga (the scorer's, a fleet robot's, a
/// cell-order leg's or piece's) is this function's; only the coverage curve's clock adds the
/// same two terms segment by segment.
pub fn drive_time_s(length_m: f64, turn_rad: f64, speed: f64, rot_speed: f64) -> f64 {
    length_m / speed + rotation_time(turn_rad, rot_speed)
}

/// The robot and the time model a plan's `time_s` follows, in words for a summary:
/// `time_s = length / speed + turning / rot_speed`, and whether turning is free (`rot_speed` =
/// 0, the default of 003's experiments: a plan's turns then cost nothing).
pub fn time_model(robot: &crate::coverage::Footprint) -> String {
    let turning = if robot.rot_speed > 0.0 {
        format!("+ turning / {} rad/s", robot.rot_speed)
    } else {
        "(rot_speed = 0: turning is free; set it for a real robot)".to_string()
    };
    format!("{} m wide; time_s = length / {} m/s {turning}", robot.width, robot.speed)
}

/// Length (m), total absolute turn (rad) and non-zero turns of a plan, summed over its paths.
pub fn plan_totals(paths: &[Vec<Point>]) -> (f64, f64, usize) {
    let (mut length, mut turn, mut turns) = (0.0, 0.0, 0);
    for p in paths {
        let (t, n) = turning(p);
        length += path_length(p);
        turn += t;
        turns += n;
    }
    (length, turn, turns)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_time_is_its_length_at_speed_plus_its_turning_at_rot_speed() {
        // Table-driven: (length, turning, speed, rot_speed, seconds).
        let table =
            [(10.0, std::f64::consts::PI, 0.2, 0.5, 50.0 + 2.0 * std::f64::consts::PI), (3.0, 7.0, 0.3, 0.0, 10.0)];
        for (length, turn, speed, rot, expected) in table {
            assert!((drive_time_s(length, turn, speed, rot) - expected).abs() < 1e-12);
        }
        let robot = crate::coverage::Footprint { width: 0.6, speed: 0.2, rot_speed: 0.5 };
        let path = [Point::new(0.0, 0.0), Point::new(2.0, 0.0), Point::new(2.0, 2.0)];
        assert_eq!(robot.path_time_s(&path), drive_time_s(4.0, std::f64::consts::FRAC_PI_2, 0.2, 0.5));
    }

    #[test]
    fn the_time_model_says_when_turning_is_free() {
        let free = crate::coverage::Footprint::default();
        assert_eq!(
            time_model(&free),
            "0.6 m wide; time_s = length / 0.2 m/s (rot_speed = 0: turning is free; set it for a real robot)"
        );
        let turning = crate::coverage::Footprint { rot_speed: 0.52, ..free };
        assert_eq!(time_model(&turning), "0.6 m wide; time_s = length / 0.2 m/s + turning / 0.52 rad/s");
    }

    #[test]
    fn square_loop_turns_and_time() {
        let pts = [Point::new(1.3, 1.3), Point::new(4.3, 1.3), Point::new(4.3, 4.3), Point::new(1.3, 1.3)];
        let (rad, n) = turning(&pts);
        assert!((rad.to_degrees() - 225.0).abs() < 1e-9);
        assert_eq!(n, 2);
        // thesis-ga §3.3 table: T_rot = 0.625 s at 2π rad/s.
        assert!((rotation_time(rad, std::f64::consts::TAU) - 0.625).abs() < 1e-12);
        assert!((path_length(&pts) - (6.0 + 18f64.sqrt())).abs() < 1e-12);
        assert_eq!(rotation_time(rad, 0.0), 0.0);
    }

    #[test]
    fn unsigned_turn_equals_eq_3_2() {
        for (a, b) in [(0.3, 2.9), (-2.0, 1.0), (3.1, -3.1), (1.0, 1.0), (0.0, 3.1)] {
            let (u, v) = (Vector::new(f64::cos(a), f64::sin(a)), Vector::new(f64::cos(b), f64::sin(b)) * 2.5);
            assert!((abs_turn_deg(u, v) - crate::geom::turn_deg(u, v).abs()).abs() < 1e-9, "{a} {b}");
        }
    }

    #[test]
    fn zero_length_segments_carry_the_heading() {
        let pts = [Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 0.0), Point::new(2.0, 0.0)];
        assert_eq!(turning(&pts), (0.0, 0));
    }
}
