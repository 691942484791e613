//! What holds the stock (issue 57): a vise's jaws and clamps, kept out of by every operation
//! and checked against every move.

use swarf::job::fixtures::{FixtureBox, Fixtures, Vise};
use swarf::job::{run_setups, Job};
use swarf::mesh::sample::two_sided_part;
use swarf::progress::Progress;
use swarf::sim::fixtures::collisions;

/// The two-sided plate held in a vise gripping 8 mm of its sides: without the vise, the
/// roughing round the plate would run into where the jaws stand; with it, every operation of
/// both setups stops short of them (and says so), and every move is checked clear of them.
#[test]
fn a_vise_holds_the_stock_and_every_operation_stops_short_of_its_jaws() {
    let free = run_setups(&Job::two_sided(), two_sided_part(), &mut Progress::none()).unwrap();
    let mut job = Job::two_sided();
    job.fixtures = Fixtures { vise: Some(Vise { grip: 8.0, ..Vise::default() }), ..Fixtures::default() };
    // The jaws as they would stand round the free job's stock: its moves run into them.
    let keep_out = job.fixtures.keep_out(&free[0].output.stock);
    let into = collisions(&free[0].output.moves, &keep_out, 0.0);
    assert!(!into.is_empty(), "the roughing never came near the jaws: the test holds nothing");
    eprintln!("without the vise: {} moves into the jaws, the deepest {:.3} mm into {}", into.len(), into.iter().map(|h| h.depth).fold(0.0, f64::max), into[0].fixture);
    let held = run_setups(&job, two_sided_part(), &mut Progress::none()).unwrap();
    for s in &held {
        let v = s.output.verification.as_ref().unwrap();
        eprintln!("{}: {}", s.name, v.report.describe());
        assert_eq!((v.report.fixtures_checked, v.report.fixture_collision_count), (2, 0), "{}", s.name);
        assert!(v.report.is_clean(), "{}", v.report.describe());
        // Checked again here, at the jaws as this setup holds them.
        assert!(collisions(&s.output.moves, &job.fixtures.keep_out(&s.output.stock), 1e-9).is_empty());
    }
    let said: Vec<String> = held.iter().flat_map(|s| s.output.warnings.iter().map(|w| w.to_string())).collect();
    assert!(said.iter().any(|w| w.contains("places stopped short of the vise's front jaw (1 mm clear of it)")), "{said:?}");
}

/// A clamp on the stock's top where the facing passes: the program that would run into it is
/// refused, the clamp named; a clamp's setting that does not fit is named at its field.
#[test]
fn a_move_into_a_clamp_is_an_error_that_names_it() {
    use swarf::operations::{Face, Operation};
    let mut job = Job::two_sided();
    let stock = run_setups(&job, two_sided_part(), &mut Progress::none()).unwrap()[0].output.stock;
    job.setups[0].operations.insert(0, Operation::Face(Face { tool: 1, ..Face::default() }));
    let clamp = FixtureBox { name: "the front left clamp".into(), min: [stock.min.x, stock.min.y, stock.max.z], max: [stock.min.x + 12.0, stock.min.y + 12.0, stock.max.z + 10.0] };
    job.setups[0].fixtures = Some(Fixtures { boxes: vec![clamp.clone()], ..Fixtures::default() });
    let e = run_setups(&job, two_sided_part(), &mut Progress::none()).and_then(|s| s.into_iter().map(|s| s.output.checked()).collect::<Result<Vec<_>, _>>()).unwrap_err().to_string();
    assert!(e.contains("run into what holds the stock: T1 into the front left clamp"), "{e}");
    // The second setup names no fixtures of its own, and the job none: nothing is checked there.
    job.setups[0].fixtures = Some(Fixtures { boxes: vec![FixtureBox { min: [0.0, 0.0, 5.0], max: [1.0, 1.0, 4.0], ..clamp }], clearance: f64::NAN, ..Fixtures::default() });
    let problems: Vec<String> = job.problems().into_iter().map(|p| p.path).collect();
    assert_eq!(problems, ["setups[0].fixtures.clearance", "setups[0].fixtures.boxes[0]"]);
}
