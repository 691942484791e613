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

/// A clamp on the stock's front edge where the facing passes: the facing lifts over it and
/// comes back down beyond it, saying so, and the program runs clear of the clamp; the same
/// program made without the clamp, verified against the job that has it, is refused with the
/// clamp named. A clamp's setting that does not fit is named at its field.
#[test]
fn a_clamp_in_the_way_is_lifted_over_and_a_program_into_it_is_refused() {
    use swarf::operations::{Face, Operation};
    let mut job = Job::two_sided();
    job.setups.clear();
    job.operations = vec![Operation::Face(Face { tool: 1, ..Face::default() })];
    let free = swarf::job::run(&job, two_sided_part(), &mut Progress::none()).unwrap();
    let stock = free.stock;
    // Over the stock's front edge, standing 10 mm above its top.
    let clamp = FixtureBox { name: "the front clamp".into(), min: [-10.0, stock.min.y - 5.0, stock.max.z], max: [10.0, stock.min.y + 12.0, stock.max.z + 10.0] };
    job.fixtures = Fixtures { boxes: vec![clamp.clone()], ..Fixtures::default() };
    let keep_out = job.fixtures.keep_out(&stock);
    assert!(!collisions(&free.moves, &keep_out, 0.0).is_empty(), "the free program must run into the clamp: the test holds nothing");
    let held = swarf::job::run(&job, two_sided_part(), &mut Progress::none()).unwrap();
    let v = held.verification.as_ref().unwrap();
    assert_eq!((v.report.fixtures_checked, v.report.fixture_collision_count), (1, 0), "{}", v.report.describe());
    assert!(collisions(&held.moves, &keep_out, 1e-9).is_empty());
    assert!(v.report.is_clean(), "{}", v.report.describe());
    let said: Vec<String> = held.warnings.iter().map(|w| w.to_string()).collect();
    assert!(said.iter().any(|w| w.contains("places stopped short of the front clamp")), "{said:?}");
    // The facing still faces the rest: it cuts nearly as long as without the clamp, and the
    // stock's top away from the clamp is faced.
    let feed = |out: &swarf::job::JobOutput| out.moves.iter().filter(|m| !m.mv.is_rapid()).map(|m| m.mv.length(m.from)).sum::<f64>();
    assert!(feed(&held) > 0.7 * feed(&free), "{} against {}", feed(&held), feed(&free));
    // Rapids run above the clamp.
    assert!(held.moves.iter().filter(|m| m.mv.is_rapid()).all(|m| collisions(std::slice::from_ref(m), &keep_out, 0.0).is_empty()));
    // The program made without the clamp is refused against the job with it.
    let checked = swarf::job::verify_gcode(&job, two_sided_part(), &free.gcode, None, &mut Progress::none()).unwrap();
    assert!(checked.report.fixture_collision_count > 0, "{}", checked.report.describe());
    assert!(checked.report.describe().contains("the front clamp"), "{}", checked.report.describe());
    job.fixtures = Fixtures { boxes: vec![FixtureBox { min: [0.0, 0.0, 5.0], max: [1.0, 1.0, 4.0], ..clamp }], clearance: f64::NAN, ..Fixtures::default() };
    let problems: Vec<String> = job.problems().into_iter().map(|p| p.path).collect();
    assert_eq!(problems, ["fixtures.clearance", "fixtures.boxes[0]"]);
}
