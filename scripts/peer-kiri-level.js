// Kiri:Moto 4.1.11's "level" operation (facing) headless, beside swarf's `face` (issue 40):
// scripts/bench-face-peers.sh runs it. The engine is the one ../shared/peers/rough/setup.sh
// installs ($PEER_ENV/kiri); it is loaded the way that folder's kiri_rough.js loads it (grid-apps'
// own CLI way: every source file evaluated in one scope).
//   node peer-kiri-level.js KIRI_DIR STL OUT.ngc tool_diam step_over_fraction down feed
// The stock is the part's box; the level pass is `down` below its top, over the whole stock
// (Kiri's "stock" option), the tool's centre to the stock's edges. G-code X/Y as the STL's.
const fs = require('fs');
const path = require('path');
const argv = process.argv.slice(2);
if (argv.length < 7) {
    console.error('usage: node peer-kiri-level.js KIRI_DIR STL OUT.ngc tool_diam step_over down feed');
    process.exit(2);
}
const [kdir, stlPath, outPath] = argv;
const [toolDiam, stepOver, down, feed] = argv.slice(3).map(Number);
const dir = path.resolve(kdir);

let exports_save = exports,
    navigator = { userAgent: '' },
    module_save = module,
    THREE = {},
    gapp = {},
    geo = {},
    noop = () => { },
    self = this.self = {
        gapp,
        THREE,
        location: { hostname: 'local', port: 0, protocol: 'fake' },
        postMessage: (msg) => { self.kiri.client.onmessage({ data: msg }); }
    };
let fetch = function (url, opts = {}) {
    if (!url.startsWith('/')) url = `${dir}/${url}`;
    let buf = fs.readFileSync(url);
    return Promise.resolve(opts.format === 'string' ? buf.toString() : opts.format === 'buffer' ? buf : opts.format === 'eval' ? eval('(' + buf + ')') : { arrayBuffer: () => buf });
};
class Worker {
    constructor(url) { }
    postMessage(msg) { setImmediate(() => { self.kiri.worker.onmessage({ data: msg }); }); }
    onmessage(msg) { }
    terminate() { }
}
function atob(a) { return Buffer.from(a).toString('base64'); }
function btoa(b) { return Buffer.from(b, 'base64').toString(); }

async function run() {
    let files = await fetch('src/cli/kiri-source.json', { format: 'eval' });
    const log = console.log;
    console.log = () => {};
    for (let file of files.map((p) => `${dir}/src/${p}.js`)) {
        let isPNG = file.indexOf('/pngjs') > 0, isClip = file.indexOf('/clip') > 0;
        let isEarcut = file.indexOf('/earcut') > 0, isTHREE = file.indexOf('/three') > 0;
        if (isTHREE) exports = {};
        if (isEarcut) module = { exports: {} };
        let clearMod = isPNG || isClip;
        if (clearMod) module = undefined;
        eval(fs.readFileSync(`${file}`).toString());
        if (isClip) ClipperLib = self.ClipperLib;
        if (isTHREE) { Object.assign(THREE, exports); exports = exports_save; }
        if (isEarcut) self.earcut = module.exports;
        if (clearMod || isEarcut) module = module_save;
    }
    let { kiri, moto, load } = self;
    const t0 = Date.now();
    let engine = kiri.newEngine();
    await engine.parse(new Uint8Array(fs.readFileSync(stlPath)).buffer);
    const tc = engine.widget.track.center;
    const cam = kiri.conf.defaults.cam;
    engine.settings.device = Object.assign(structuredClone(cam.d), {
        mode: 'CAM', deviceName: 'peer-linuxcnc', spindleMax: 30000, bedWidth: 1000, bedDepth: 1000, maxHeight: 300,
        gcodeSpace: true, gcodeStrip: false, gcodeFExt: 'ngc',
        gcodePre: ['G21', 'G90', 'G17', 'G94'], gcodePost: ['M5', 'M30'], gcodeDwell: ['G4 P{time}'],
        gcodeChange: ['T{tool} M6'], gcodeSpindle: ['M3 S{speed}']
    });
    engine.settings.process = Object.assign(structuredClone(cam.p), {
        camStockOffset: true, camStockX: 0, camStockY: 0, camStockZ: 0,
        camZAnchor: 'top', camZOffset: 0, camZTop: 0, camZBottom: 0, camZThru: 0,
        camZClearance: 5, camOriginTop: false, camOriginCenter: false,
        camFastFeed: 6000, camFastFeedZ: 300, camTolerance: 0, camDepthFirst: false,
        ops: [{ type: 'level', tool: 9001, spindle: 10000, step: stepOver, rate: feed, down, stock: true }]
    });
    engine.settings.tools = [{
        id: 9001, number: 1, name: `flat ${toolDiam}mm`, type: 'endmill',
        shaft_diam: toolDiam, shaft_len: 40, flute_diam: toolDiam, flute_len: 60, taper_tip: 0, metric: true
    }];
    engine.setMode('CAM');
    const b = engine.widget.getBoundingBox();
    const stock = { x: b.max.x - b.min.x, y: b.max.y - b.min.y, z: b.max.z - b.min.z, center: { x: (b.max.x + b.min.x) / 2, y: (b.max.y + b.min.y) / 2, z: 0 } };
    stock.center.z = stock.z / 2;
    engine.settings.stock = stock;
    engine.widget.setTopZ(stock.z);
    engine.settings.origin = { x: -tc.dx, y: tc.dy, z: 0 };
    await engine.slice();
    await engine.prepare();
    let gcode = await engine.export();
    const t1 = Date.now();
    console.log = log;
    // Z words back to the STL's frame; Kiri's ';' comments as LinuxCNC's.
    gcode = gcode.split(/\r?\n/).map((line) => {
        if (line.startsWith(';')) return '(' + line.substring(1).replace(/[()]/g, '').trim() + ')';
        let semi = line.indexOf(';');
        let code = semi >= 0 ? line.substring(0, semi) : line;
        return code.replace(/Z(-?[0-9.]+)/g, (m, v) => 'Z' + (parseFloat(v) + tc.dz).toFixed(3));
    }).join('\n') + '\n';
    fs.writeFileSync(outPath, gcode);
    console.error(JSON.stringify({ peer: `kiri:moto ${kiri.version} level`, compute_s: (t1 - t0) / 1000, stock: { x: stock.x, y: stock.y } }));
}
run().catch((e) => { console.error('ERROR', e); process.exit(1); });
