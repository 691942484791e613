# The roughing job of issue 12's settings (a flat end, step-over 0.4, no allowance, the stock the
# part's box, rapids at 5000 mm/min, verification off), sourced by scripts/rough-speed.sh and
# scripts/octree-speed.sh: `job KIND STEPDOWN DIAMETER...` prints it, its tools flat ends of
# those diameters (numbered from 1; the octree takes them all as its library, the other kinds
# the first at STEPDOWN).
job() {
  target/release/swarf job | python3 -c "
import json, sys
kind, stepdown, ds = sys.argv[1], float(sys.argv[2]), [float(d) for d in sys.argv[3:]]
j = json.load(sys.stdin)
j['part'] = {'placement': 'keep'}
j['stock'].update({'marginXy': 0, 'marginTop': 0, 'marginBottom': 0})
j['post']['rapidRate'] = 5000
j['simulation']['verify'] = False
j['tools'] = [{'number': n + 1, 'name': 'f%g' % d, 'shape': 'flat', 'diameter': d, 'fluteLength': 50, 'feedRate': 1000, 'plungeRate': 250} for n, d in enumerate(ds)]
op = {'kind': kind, 'stepoverFraction': 0.4, 'allowance': 0, 'leaveStock': 0, 'grid': 0.5}
op.update({'tool': 1, 'stepdown': stepdown} if kind != 'roughOctree' else {'tools': list(range(1, len(ds) + 1))})
j['operations'] = [op]
json.dump(j, sys.stdout)" "$@"
}
