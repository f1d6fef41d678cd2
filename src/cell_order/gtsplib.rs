//! The tour problem written out as a GTSPLIB instance, so that an established generalised-TSP
//! solver (GLKH, GLNS) or an asymmetric-TSP solver after the Noon–Bean transform (LKH-3) can
//! check covga's searches on exactly the costs they optimise.
//!
//! Node 1 stands for the stations (leaving it is leaving the start, entering it is arriving at
//! the end station); nodes 2, 3, … are the candidate sweeps, cell after cell in the order of
//! [`Instance::flat`]; each cell's candidates form one set. The arc from node `a` to node `b`
//! weighs the leg from `a`'s exit to `b`'s entry plus `b`'s own time (a sweep's time is charged
//! on the arc that enters it), so that a tour's weight is [`Instance::time`]. Weights are whole
//! milliseconds ([`WEIGHT_S`]), since GTSPLIB solvers read integers.

use super::sweeps::CellSweeps;
use super::tour::{Instance, Tour};

/// Seconds per unit of weight.
pub const WEIGHT_S: f64 = 1e-3;

/// The heaviest weight a GTSPLIB solver reads: GLKH, GLNS and LKH-3 read the matrix into
/// 32-bit integers, so a heavier arc would wrap or be cut short there.
pub const MAX_WEIGHT: i64 = i32::MAX as i64;

/// The weight of an arc of `seconds`.
fn weight(seconds: f64) -> i64 {
    (seconds / WEIGHT_S).round() as i64
}

/// The weight of the arc from node `from` to node `to` (0-based: 0 the stations, `1 + g` the
/// flat candidate `g`); 0 from a node to itself.
pub fn arc_weight(inst: &Instance, from: usize, to: usize) -> i64 {
    if from == to {
        return 0;
    }
    let candidate = |node: usize| node.checked_sub(1);
    let (a, b) = (candidate(from), candidate(to));
    weight(inst.leg(a, b) + b.map_or(0.0, |g| inst.own(g)))
}

/// The weight of the instance's heaviest arc.
pub fn heaviest_arc(inst: &Instance) -> i64 {
    let nodes = 1 + (0..inst.cells()).map(|k| inst.choices(k)).sum::<usize>();
    (0..nodes).flat_map(|from| (0..nodes).map(move |to| arc_weight(inst, from, to))).max().unwrap_or(0)
}

/// Refuses an instance whose heaviest arc is past [`MAX_WEIGHT`] (a robot so slow that a leg
/// takes weeks), naming the robot's speeds that make it so.
pub fn check_weights(inst: &Instance, robot: &crate::coverage::Footprint) -> Result<(), String> {
    let heaviest = heaviest_arc(inst);
    if heaviest <= MAX_WEIGHT {
        return Ok(());
    }
    Err(format!(
        "at robot.speed = {} m/s and robot.rot_speed = {} rad/s an arc of the tour problem takes {:.0} s \
         ({heaviest} ms), past the {MAX_WEIGHT} ms (about 24.8 days) a GTSPLIB solver reads as a 32-bit \
         weight; raise robot.speed (and robot.rot_speed where turning is that slow); nothing written",
        robot.speed,
        robot.rot_speed,
        heaviest as f64 * WEIGHT_S,
    ))
}

/// The instance as GTSPLIB text (`TYPE : AGTSP`, a full matrix, one set per cell and one for
/// the stations), named `name`.
pub fn instance_text(inst: &Instance, name: &str) -> String {
    use std::fmt::Write;
    let nodes = 1 + (0..inst.cells()).map(|k| inst.choices(k)).sum::<usize>();
    let mut out = String::with_capacity(nodes * nodes * 8 + 256);
    let _ = writeln!(out, "NAME : {name}");
    out.push_str("TYPE : AGTSP\n");
    let _ = writeln!(
        out,
        "COMMENT : covga cell-order tour problem; weights in milliseconds; node 1 the stations, \
         then each cell's candidate sweeps"
    );
    let _ = writeln!(out, "DIMENSION : {nodes}");
    let _ = writeln!(out, "GTSP_SETS : {}", inst.cells() + 1);
    out.push_str("EDGE_WEIGHT_TYPE : EXPLICIT\nEDGE_WEIGHT_FORMAT : FULL_MATRIX\nEDGE_WEIGHT_SECTION\n");
    for from in 0..nodes {
        for to in 0..nodes {
            let sep = if to + 1 == nodes { '\n' } else { ' ' };
            let _ = write!(out, "{}{sep}", arc_weight(inst, from, to));
        }
    }
    out.push_str("GTSP_SET_SECTION\n1 1 -1\n");
    for k in 0..inst.cells() {
        let _ = write!(out, "{}", k + 2);
        for c in 0..inst.choices(k) {
            let _ = write!(out, " {}", inst.flat(k, c) + 2);
        }
        out.push_str(" -1\n");
    }
    out.push_str("EOF\n");
    out
}

/// What each node of [`instance_text`] is, as CSV: its number, its cell and the candidate's
/// index in the cell, lane direction and entry corner (as `summary.json`'s `tour` names them);
/// the stations' row leaves the last four empty.
pub fn nodes_csv(inst: &Instance, sweeps: &CellSweeps) -> String {
    use std::fmt::Write;
    let mut out = String::from("node,cell,choice,direction_deg,entry\n1,,,,\n");
    for (k, cell) in sweeps.cells.iter().enumerate() {
        for (c, w) in cell.iter().enumerate() {
            let _ = writeln!(out, "{},{k},{c},{},{}", inst.flat(k, c) + 2, w.direction_deg, w.entry);
        }
    }
    out
}

/// The weight of `tour` in the instance: its nodes from the stations back to them.
pub fn tour_weight(inst: &Instance, tour: &Tour) -> i64 {
    let mut nodes = vec![0];
    nodes.extend(tour.order.iter().map(|&k| 1 + inst.flat(k as usize, tour.choice[k as usize] as usize)));
    nodes.push(0);
    nodes.windows(2).map(|w| arc_weight(inst, w[0], w[1])).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell_order::tour::tests::line;

    #[test]
    fn a_tour_weighs_its_mission_time_within_the_rounding() {
        let inst = line(5);
        let mut tour = crate::cell_order::search::nearest_neighbour(&inst);
        for t in [tour.clone(), {
            tour.order.reverse();
            tour
        }] {
            let ms = tour_weight(&inst, &t) as f64 * WEIGHT_S;
            // Half a unit per arc at most.
            assert!((ms - inst.time(&t)).abs() <= 0.5 * WEIGHT_S * (t.order.len() + 1) as f64, "{ms}");
        }
    }

    #[test]
    fn the_text_holds_every_arc_and_one_set_per_cell_and_the_stations() {
        let inst = line(3);
        let text = instance_text(&inst, "line");
        let nodes = 1 + (0..3).map(|k| inst.choices(k)).sum::<usize>();
        assert!(text.contains(&format!("DIMENSION : {nodes}\n")), "{text}");
        assert!(text.contains("GTSP_SETS : 4\n"));
        let matrix: Vec<&str> = text
            .lines()
            .skip_while(|l| *l != "EDGE_WEIGHT_SECTION")
            .skip(1)
            .take_while(|l| *l != "GTSP_SET_SECTION")
            .collect();
        assert_eq!(matrix.len(), nodes);
        for (from, row) in matrix.iter().enumerate() {
            let weights: Vec<i64> = row.split(' ').map(|w| w.parse().unwrap()).collect();
            let expected: Vec<i64> = (0..nodes).map(|to| arc_weight(&inst, from, to)).collect();
            assert_eq!(weights, expected);
        }
        let sets: Vec<&str> = text.lines().skip_while(|l| *l != "GTSP_SET_SECTION").skip(1).collect();
        assert_eq!(sets[0], "1 1 -1");
        let members: Vec<usize> =
            sets[1..4].iter().flat_map(|l| l.split(' ').skip(1)).filter_map(|n| n.parse().ok()).collect();
        assert_eq!(members, (2..=nodes).collect::<Vec<_>>());
        assert_eq!(sets[4], "EOF");
    }

    #[test]
    fn the_heaviest_arc_is_the_largest_weight_of_the_matrix() {
        let inst = line(4);
        let nodes = 1 + (0..4).map(|k| inst.choices(k)).sum::<usize>();
        let all: Vec<i64> =
            (0..nodes).flat_map(|f| (0..nodes).map(move |t| (f, t))).map(|(f, t)| arc_weight(&inst, f, t)).collect();
        assert_eq!(heaviest_arc(&inst), *all.iter().max().unwrap());
        assert!(heaviest_arc(&inst) > 0);
    }
}
