//! Every bad input the reliability passes found, as a table: each exits 2 with one line that
//! names the file, key or line, and writes nothing.

use super::{GRID, SMALL, THESIS_1_PGM, children_peak_rss_bytes, listing};
use crate::common::covga_in;

struct Case {
    /// What the case is about.
    name: &'static str,
    /// Files written into the case's folder first: name and contents.
    files: &'static [(&'static str, &'static str)],
    /// Arguments; `OUT` is the results folder that must not be created.
    args: &'static [&'static str],
    /// A fragment the one error line must contain.
    needle: &'static str,
}

const CASES: &[Case] = &[
    Case {
        name: "empty experiment file",
        files: &[("e.toml", "")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "e.toml: sets nothing",
    },
    Case {
        name: "only comments",
        files: &[("e.toml", "# planner = \"thesis\"\n\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "sets nothing",
    },
    Case {
        name: "bare image map without resolution in TOML",
        files: &[("e.toml", "[map]\nsource = \"m.pgm\"\n"), ("m.pgm", "P2\n2 2\n255\n254 254 254 254\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`map.resolution` is missing: the bare image `m.pgm`",
    },
    Case {
        name: "robot wider than the map",
        files: &[("e.toml", "[robot]\nwidth = 60\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`robot.width` = 60 m is wider",
    },
    Case {
        name: "huge robot number shortened",
        files: &[("e.toml", "[robot]\nwidth = 1e300\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "= 1e300 m",
    },
    Case {
        name: "population that cannot fit the memory limit",
        files: &[("e.toml", SMALL)],
        args: &["run", "e.toml", "--out", "OUT", "--max-memory", "10k"],
        needle: "`thesis.pop_min` would need up to about",
    },
    Case {
        name: "absurd population refused at once",
        files: &[("e.toml", "[thesis]\npop_min = 1000000\ninit_actions = 100000\nmax_genome_len = 1000000\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "1000000 individuals of up to 1000000 actions",
    },
    Case {
        name: "bad --max-memory",
        files: &[("e.toml", SMALL)],
        args: &["run", "e.toml", "--out", "OUT", "--max-memory", "8X"],
        needle: "unknown unit `X`",
    },
    Case {
        name: "unknown key",
        files: &[("e.toml", "[thesis]\ncolour = 3\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "unknown field `colour`",
    },
    Case {
        name: "retrain region over the whole map (A_pix = 0)",
        files: &[(
            "e.toml",
            "[budget]\niterations = 10\n[retrain]\nat_iteration = 5\nregion = [0.0, 0.0, 11.0, 11.0]\n",
        )],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`retrain.region` = [0.0, 0.0, 11.0, 11.0] covers every free cell",
    },
    Case {
        name: "missing experiment file",
        files: &[],
        args: &["run", "absent.toml", "--out", "OUT"],
        needle: "absent.toml",
    },
    Case {
        name: "results folder is a file (run)",
        files: &[("e.toml", SMALL), ("taken", "x")],
        args: &["run", "e.toml", "--out", "taken/OUT"],
        needle: "taken/OUT: cannot create the results folder",
    },
    Case {
        name: "waypoint hallway too wide for the map",
        files: &[("e.toml", "planner = \"waypoint\"\n[map]\nsource = \"thesis-1\"\n[waypoint]\nhallway = 30\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`waypoint.hallway` = 30 m is out of range: allowed [max(2 x scale, map resolution), the map's longer side = 11 m]",
    },
    Case {
        name: "waypoint hallway of infinite width",
        files: &[("e.toml", "planner = \"waypoint\"\n[map]\nsource = \"thesis-1\"\n[waypoint]\nhallway = inf\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`waypoint.hallway` = inf m is out of range",
    },
    Case {
        name: "waypoint paths shorter than two waypoints",
        files: &[("e.toml", "planner = \"waypoint\"\n[map]\nsource = \"thesis-1\"\n[waypoint]\nl_min = 0\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`waypoint.l_min` needs 2 <= l_min (0) <= l_init (150)",
    },
    Case {
        name: "a wall clock beyond its bound names the bound",
        files: &[("e.toml", "[budget]\nwall_clock_s = 1e18\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`budget.wall_clock_s` = 1e18 is out of range: allowed [0, 1e9] seconds",
    },
    Case {
        name: "a camera range beyond its bound names the bound",
        files: &[("e.toml", "[scorer.camera]\nd_min = 1e18\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`scorer.camera.d_min` = 1e18 is out of range: allowed [0, 1e6] metres",
    },
    Case {
        name: "waypoint paths of ten million waypoints",
        files: &[("e.toml", "planner = \"waypoint\"\n[map]\nsource = \"thesis-1\"\n[waypoint]\nl_max = 10000000\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`waypoint.l_max` = 10000000 is out of range [l_init, 100000]",
    },
    Case {
        name: "a billion shortcut tries per mutation",
        files: &[(
            "e.toml",
            "planner = \"waypoint\"\n[map]\nsource = \"thesis-1\"\n[waypoint]\nb_instances = 1000000000\n",
        )],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`waypoint.b_instances` = 1000000000 is out of range [0, 10000]",
    },
    Case {
        name: "a fan view deeper than the map",
        files: &[(
            "e.toml",
            "planner = \"waypoint\"\n[map]\nsource = \"thesis-1\"\n[waypoint]\nview_shape = \"fan\"\n[scorer.camera]\nd_max = 1000\n",
        )],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`scorer.camera.d_max` = 1000 m is beyond the map's diagonal of 15.56 m",
    },
    Case {
        name: "a wall clock spent in the waypoint precompute",
        files: &[("e.toml", "planner = \"waypoint\"\n[map]\nsource = \"thesis-1\"\n[budget]\nwall_clock_s = 1e-6\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "the wall clock of 0.000001 s (`budget.wall_clock_s`) ran out while placing the waypoints",
    },
    Case {
        name: "path point outside the map",
        files: &[("p.csv", "x_m,y_m\n1.3,1.3\n100,100\n")],
        args: &["eval", "--path", "p.csv", "--map", "thesis-1", "--out", "OUT"],
        needle: "(100, 100) m is outside map",
    },
    Case {
        name: "missing path file has no line 0",
        files: &[],
        args: &["eval", "--path", "absent.csv", "--out", "OUT"],
        needle: "absent.csv: cannot read path file",
    },
    Case {
        name: "image header declaring a huge map",
        files: &[("huge.pgm", "P5\n100000 100000\n255\n")],
        args: &["eval", "--map", "huge.pgm", "--resolution", "0.05", "--out", "OUT"],
        needle: "a map must have between 1 and",
    },
    Case {
        name: "conditional whose `when` never matches",
        files: &[(
            "g.toml",
            "[base]\n[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n[[conditional]]\nwhen = { \"thesis.selection\" = \"rrws\" }\naxes = { \"thesis.selection_pressure\" = [1.5, 2.0] }\n",
        )],
        args: &["grid", "g.toml", "--out", "OUT"],
        needle: "`conditional[0].when` (thesis.selection = rrws) matches no run",
    },
    Case {
        name: "swept key the selection ignores",
        files: &[("g.toml", "[base]\n[axes]\n\"thesis.tournament_size\" = [3, 7]\n")],
        args: &["grid", "g.toml", "--out", "OUT"],
        needle: "`thesis.tournament_size` is swept but ignored",
    },
    Case {
        name: "swept selection pressure under the cell-order GA's tournament",
        files: &[(
            "g.toml",
            "[base]\nplanner = \"cell_order\"\n[axes]\n\"cell_order.selection_pressure\" = [1.2, 1.8]\n",
        )],
        args: &["grid", "g.toml", "--out", "OUT"],
        needle: "`cell_order.selection_pressure` is swept but ignored in run",
    },
    Case {
        name: "swept GA key under the exact solver",
        files: &[(
            "g.toml",
            "[base]\nplanner = \"cell_order\"\n[base.cell_order]\nsolver = \"exact\"\n[axes]\n\"cell_order.population\" = [10, 20]\n",
        )],
        args: &["grid", "g.toml", "--out", "OUT"],
        needle: "runs no GA",
    },
    Case {
        name: "swept pattern angle under cell_order names the planner in its hint",
        files: &[(
            "g.toml",
            "[base]\n[axes]\n\"planner\" = [\"cell_order\", \"spiral\"]\n\"pattern.angle_deg\" = [0.0, 90.0]\n",
        )],
        args: &["grid", "g.toml", "--out", "OUT"],
        needle: "when = { \"planner\" = \"…\" }",
    },
    Case {
        name: "grid over the memory limit",
        files: &[("g.toml", GRID)],
        args: &["grid", "g.toml", "--out", "OUT", "--jobs", "2", "--max-memory", "10k"],
        needle: "× 2 runs at once",
    },
    Case {
        name: "absurd grid counted before it is expanded",
        files: &[(
            "g.toml",
            "[base]\n[axes]\n\"robot.speed\" = [0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0]\n\"thesis.pop_min\" = [1,2,3,4,5,6,7,8,9,10]\n\"thesis.init_actions\" = [1,2,3,4,5,6,7,8,9,10]\n\"thesis.p_c\" = [0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0]\n\"thesis.c_len\" = [0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0]\n\"thesis.p_ma\" = [0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0]\n\"thesis.p_mi\" = [0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0]\n",
        )],
        args: &["grid", "g.toml", "--dry-run", "--out", "OUT"],
        needle: "expands to up to 1.000e7 runs",
    },
    Case {
        name: "results folder is a file (grid)",
        files: &[("g.toml", GRID), ("taken", "x")],
        args: &["grid", "g.toml", "--out", "taken/OUT"],
        needle: "taken/OUT",
    },
    Case {
        name: "an axis that lists one value twice",
        files: &[("g.toml", "[base]\n[axes]\n\"thesis.c_len\" = [0.1, 0.1]\n")],
        args: &["grid", "g.toml", "--dry-run", "--out", "OUT"],
        needle: "`axes.\"thesis.c_len\"` lists the value 0.1 twice",
    },
    Case {
        name: "an axis whose values read as one setting",
        files: &[("g.toml", "[base]\n[axes]\n\"thesis.p_c\" = [1, 1.0]\n")],
        args: &["grid", "g.toml", "--dry-run", "--out", "OUT"],
        needle: "`axes` two runs resolve to one configuration",
    },
    Case {
        name: "the seed swept as an axis",
        files: &[("g.toml", "[base]\n[axes]\n\"seed\" = [1, 2]\n")],
        args: &["grid", "g.toml", "--dry-run", "--out", "OUT"],
        needle: "`axes.\"seed\"` cannot be swept: the grid derives each run's seed",
    },
    Case {
        name: "the output folder swept as an axis",
        files: &[("g.toml", "[base]\n[axes]\n\"output.dir\" = [\"a\", \"b\"]\n")],
        args: &["grid", "g.toml", "--dry-run", "--out", "OUT"],
        needle: "`axes.\"output.dir\"` cannot be swept",
    },
    Case {
        name: "D1: a bare image at a billion metres per pixel",
        files: &[],
        args: &["eval", "--map", THESIS_1_PGM, "--resolution", "1e9", "--start", "2.5e10,2.5e10", "--out", "OUT"],
        needle: "has cells of 1e9 m: the camera coverage eval reports",
    },
    Case {
        name: "D10: eval on a map of 10 m cells names the resolution, not a waypoint key",
        files: &[],
        args: &["eval", "--map", THESIS_1_PGM, "--resolution", "10", "--start", "50,50", "--out", "OUT"],
        needle: "needs cells of at most 1.5 m; give a finer map (`--resolution`",
    },
    Case {
        name: "D2: a robot a picometre wide (eval)",
        files: &[],
        args: &["eval", "--map", "thesis-1", "--width", "1e-12", "--out", "OUT"],
        needle: "a robot 1e-12 m wide needs about 1.556e13 lanes",
    },
    Case {
        name: "D2: a robot a micrometre wide (run)",
        files: &[("e.toml", "planner = \"boustrophedon\"\n[robot]\nwidth = 1e-6\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`robot.width` a robot 1e-6 m wide needs about 1.556e7 lanes",
    },
    Case {
        name: "D4: two conditionals that both apply",
        files: &[(
            "g.toml",
            "[base]\n[axes]\n\"thesis.c_len\" = [0.1]\n[[conditional]]\nwhen = { \"thesis.c_len\" = 0.1 }\naxes = { \"thesis.p_ma\" = [0.1] }\n[[conditional]]\nwhen = { \"thesis.c_len\" = 0.1 }\naxes = { \"thesis.p_ma\" = [0.2] }\n",
        )],
        args: &["grid", "g.toml", "--dry-run", "--out", "OUT"],
        needle: "`conditional[1].axes.\"thesis.p_ma\"` is also set by conditional[0]",
    },
    Case {
        name: "D9: an experiment file that never ends",
        files: &[],
        args: &["run", "/dev/zero", "--out", "OUT"],
        needle: "/dev/zero: cannot read experiment file: larger than 16 MiB",
    },
    Case {
        name: "D13: a shard of a Slurm array",
        files: &[("g.toml", GRID)],
        args: &["grid", "g.toml", "--shard", "1/2", "--slurm", "--out", "OUT"],
        needle: "'--shard <SHARD>' cannot be used with '--slurm'",
    },
    Case {
        name: "D11: area division with a robot too slow for one lane",
        files: &[(
            "fleet.toml",
            "[[robots]]\nname = \"slow\"\nwidth = 0.6\nspeed = 0.001\nstart = [1.3, 1.3]\n[[robots]]\nname = \"fast\"\nwidth = 0.6\nspeed = 0.2\nstart = [9.7, 1.3]\n",
        )],
        args: &["eval", "--fleet", "fleet.toml", "--divide", "--out", "OUT"],
        needle: "robot \"slow\" was given 0.44 m² (11 cells): its share of the area by width × speed",
    },
    Case { name: "merge of a folder with no shards", files: &[], args: &["merge", "."], needle: "no runs.csv" },
    Case {
        name: "merge of a folder that is not a study",
        files: &[("runs.csv", "run_id\n")],
        args: &["merge", "."],
        needle: "not a study folder",
    },
    Case {
        name: "merge of a garbage shard file",
        files: &[("runs-shard-0-of-1.csv", "garbage\n\"unclosed,quote\n"), ("study.json", "{}")],
        args: &["merge", "."],
        needle: "runs-shard-0-of-1.csv: not a covga runs file",
    },
    Case {
        name: "eval results folder is a file",
        files: &[("taken", "x")],
        args: &["eval", "--map", "thesis-1", "--out", "taken/OUT"],
        needle: "taken/OUT: cannot create the output folder",
    },
    Case {
        name: "negative coordinates as typed, outside the map",
        files: &[],
        args: &["eval", "--map", "thesis-1", "--start", "-17.4,-1.55", "--out", "OUT"],
        needle: "--start (-17.4, -1.55) m is outside map",
    },
    Case { name: "report of a non-study folder", files: &[], args: &["report", "."], needle: "not a study folder" },
    Case {
        name: "start where the robot's body touches a wall",
        files: &[("e.toml", "[map]\nsource = \"thesis-1\"\n[stations]\nstart = [1.1, 5.0]\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`stations.start` a 0.6 m robot does not fit at the start (1.1, 5) m",
    },
    Case {
        name: "cell_order from a corner of an all-free map",
        files: &[
            (
                "e.toml",
                "planner = \"cell_order\"\n[map]\nsource = \"free.pgm\"\nresolution = 0.2\n[stations]\nstart = [0.0, 0.0]\n",
            ),
            (
                "free.pgm",
                "P2\n10 10\n255\n254 254 254 254 254 254 254 254 254 254\n254 254 254 254 254 254 254 254 254 254\n254 254 254 254 254 254 254 254 254 254\n254 254 254 254 254 254 254 254 254 254\n254 254 254 254 254 254 254 254 254 254\n254 254 254 254 254 254 254 254 254 254\n254 254 254 254 254 254 254 254 254 254\n254 254 254 254 254 254 254 254 254 254\n254 254 254 254 254 254 254 254 254 254\n254 254 254 254 254 254 254 254 254 254\n",
            ),
        ],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "does not fit at the start (0, 0) m: its body would touch a wall, an unknown cell or the map's edge (clearance there 0.0000 m",
    },
    Case {
        name: "eval pattern from a station where the body does not fit",
        files: &[],
        args: &["eval", "--map", "thesis-1", "--pattern", "boustrophedon", "--start", "1.1,5", "--out", "OUT"],
        needle: "does not fit at --start (1.1, 5) m",
    },
    Case {
        name: "huge pattern angle for a seeded thesis run",
        files: &[("e.toml", "[thesis]\nseed_population = [\"boustrophedon\"]\n[pattern]\nangle_deg = 1e308\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`pattern.angle_deg` = 1e308",
    },
    Case {
        name: "nan pattern angle for a seeded thesis run",
        files: &[("e.toml", "[thesis]\nseed_population = [\"boustrophedon\"]\n[pattern]\nangle_deg = nan\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`pattern.angle_deg`",
    },
    Case {
        name: "eval angle out of range",
        files: &[],
        args: &["eval", "--map", "thesis-1", "--angle", "1e308", "--out", "OUT"],
        needle: "--angle = 1e308 is out of range",
    },
    Case {
        name: "seed bound under Elite with re-initialisation",
        files: &[(
            "e.toml",
            "[map]\nsource = \"thesis-1\"\n[thesis]\nselection = \"elite\"\np_mi = 0.1\nseed_population = [\"spiral\"]\nseed_bound = \"dominate\"\n",
        )],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "needs thesis.p_mi = 0 (it is 0.1)",
    },
    Case {
        name: "run into a folder holding another run's files",
        files: &[("e.toml", SMALL), ("taken/best_genome.csv", "role,alpha_deg,dist_m\n")],
        args: &["run", "e.toml", "--out", "taken"],
        needle: "taken: holds files of another run (best_genome.csv)",
    },
    Case {
        name: "report of a study with a run recorded twice",
        files: &[("study.json", "{\"runs\": 2}"), ("runs.csv", "run_id,cov_final_free\na,0.5\na,0.6\n")],
        args: &["report", "."],
        needle: "run a is recorded twice",
    },
    Case {
        name: "report of a share above 1",
        files: &[("study.json", "{\"runs\": 1}"), ("runs.csv", "run_id,cov_final_free\na,1.7\n")],
        args: &["report", "."],
        needle: "run a has `cov_final_free` = 1.7 (line 2): allowed [0, 1]",
    },
    Case {
        name: "report of a negative time",
        files: &[("study.json", "{\"runs\": 1}"), ("runs.csv", "run_id,time_s\na,-5\n")],
        args: &["report", "."],
        needle: "run a has `time_s` = -5 (line 2): allowed [0, inf]",
    },
    Case {
        name: "report of a corrupt study.json",
        files: &[("study.json", "{\"runs\": "), ("runs.csv", "run_id,time_s\na,5\n")],
        args: &["report", "."],
        needle: "study.json: not a covga study description",
    },
    Case {
        name: "path file whose index is out of order",
        files: &[("p.csv", "index,x_m,y_m\n0,5,5\n2,6,5\n1,6,6\n")],
        args: &["eval", "--map", "thesis-1", "--path", "p.csv", "--out", "OUT"],
        needle: "p.csv:3: `index` = `2` where 1 was expected",
    },
    Case {
        name: "path file whose index is not a number",
        files: &[("p.csv", "index,x_m,y_m\na,5,5\n")],
        args: &["eval", "--map", "thesis-1", "--path", "p.csv", "--out", "OUT"],
        needle: "p.csv:2: `index` = `a` where 0 was expected",
    },
    Case {
        name: "path file that is a folder",
        files: &[("p.csv/x", "")],
        args: &["eval", "--map", "thesis-1", "--path", "p.csv", "--out", "OUT"],
        needle: "p.csv: is not a regular file",
    },
    Case {
        name: "maps into a file",
        files: &[("taken", "x")],
        args: &["maps", "--out", "taken"],
        needle: "taken: cannot write the map files",
    },
    Case {
        name: "an obstacle rectangle between cell centres",
        files: &[],
        args: &[
            "eval",
            "--map",
            "thesis-1",
            "--pattern",
            "boustrophedon",
            "--obstacle",
            "5.01,5.01,5.02,5.02",
            "--out",
            "OUT",
        ],
        needle: "--obstacle 5.01,5.01,5.02,5.02: holds no free cell centre of map `thesis-1`",
    },
    Case {
        name: "routed moves for a robot that fits nowhere near its start",
        files: &[(
            "e.toml",
            "planner = \"thesis\"\n[map]\nsource = \"thesis-2\"\n[robot]\nwidth = 3.5\n[stations]\nstart = [1.3, 1.3]\n\
             [thesis]\nmoves = \"routed\"\n[budget]\niterations = 1\n",
        )],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`stations.start` a 3.5 m robot does not fit at the start",
    },
    Case {
        name: "a resolution for a preset map",
        files: &[("e.toml", "[map]\nsource = \"thesis-1\"\nresolution = 0.1\n")],
        args: &["run", "e.toml", "--out", "OUT"],
        needle: "`resolution` = 0.1 is out of range: a resolution applies to a bare PGM/PNG image only",
    },
    Case {
        name: "exact cell order on more cells than it takes, in a grid",
        files: &[(
            "g.toml",
            "[base]\nplanner = \"cell_order\"\n[base.map]\nsource = \"office\"\n[base.stations]\nstart = [2.0, 2.0]\n\
             [axes]\n\"cell_order.solver\" = [\"ga\", \"exact\"]\n",
        )],
        args: &["grid", "g.toml", "--out", "OUT"],
        needle: "`cell_order.solver` = \"exact\" takes at most 12 cells; map `office` has 17",
    },
    Case {
        name: "area division of robots starting in one cell, in a grid",
        files: &[(
            "g.toml",
            "[base]\n[base.fleet]\nmode = \"divide\"\n[[base.robots]]\nname = \"a\"\nstart = [1.3, 1.3]\n\
             [[base.robots]]\nname = \"b\"\nstart = [1.35, 1.3]\n[axes]\n\"fleet.angle_deg\" = [0.0, 90.0]\n",
        )],
        args: &["grid", "g.toml", "--out", "OUT"],
        needle: "`robots[1].start` (robot \"b\") starts in the same cell as robots[0]",
    },
];

#[test]
fn every_bad_input_exits_2_with_one_line_and_writes_nothing() {
    let mut failures = Vec::new();
    for case in CASES {
        let dir = tempfile::tempdir().unwrap();
        for (name, text) in case.files {
            let path = dir.path().join(name);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(path, text).unwrap();
        }
        let before = listing(dir.path());
        let started = std::time::Instant::now();
        let o = covga_in(dir.path(), &case.args.iter().map(|a| a.to_string()).collect::<Vec<_>>());
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        let problems = [
            (o.status.code() != Some(2)).then(|| format!("exit {:?}", o.status.code())),
            (!err.contains(case.needle)).then(|| format!("no `{}`", case.needle)),
            // (The argument parser adds its usage line and pointer to --help after its one line.)
            (err.trim()
                .lines()
                .filter(|l| !l.trim().is_empty() && !l.starts_with("For more information") && !l.starts_with("Usage: "))
                .count()
                != 1)
                .then(|| "not one line".to_string()),
            err.contains("panicked").then(|| "panicked".to_string()),
            (listing(dir.path()) != before).then(|| format!("wrote {:?}", listing(dir.path()))),
            // Every refusal comes within 5 s, whatever the input asks for.
            (started.elapsed().as_secs_f64() > 5.0).then(|| format!("slow to refuse ({:?})", started.elapsed())),
        ];
        for p in problems.into_iter().flatten() {
            failures.push(format!("{}: {p}; stderr: {}", case.name, err.trim()));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // The largest child this test process has waited for: every refusal above stayed below it.
    let peak = children_peak_rss_bytes();
    eprintln!("peak resident memory of the largest child so far: {} MB", peak >> 20);
    assert!(peak < 500 << 20, "a refusal peaked at {} MB of resident memory (bound 500 MB)", peak >> 20);
}
