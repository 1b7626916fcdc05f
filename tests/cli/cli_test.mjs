// Driver of the prt-bake CLI tests: runs the real binary and checks exit statuses, stderr
// messages and JSON output.
// Usage: node cli_test.mjs CASE PRT_BAKE FIXTURES_DIR WORK_DIR BLENDER_WORLD_DIR
// Each CASE is one ctest test (cli_tests.cmake); every failed check is listed, then the
// process exits 1.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

const [caseName, bake, fixturesDir, workDir, blenderDir] = process.argv.slice(2);
if (!blenderDir) {
  console.error('usage: node cli_test.mjs CASE PRT_BAKE FIXTURES_DIR WORK_DIR BLENDER_WORLD_DIR');
  process.exit(2);
}

// prt-bake's exit statuses (native/exit_status.h, docs/baker.md "Exit status").
const EXIT_USAGE = 2, EXIT_NOT_FOUND = 3, EXIT_INVALID_INPUT = 4, EXIT_RESOURCE_EXHAUSTED = 6;

const failures = [];
let checks = 0;
function check(ok, message) {
  checks++;
  if (!ok) failures.push(message);
  return ok;
}

const fixture = (name) => path.join(fixturesDir, name);
function workFile(name, data) {
  const p = path.join(workDir, name);
  fs.writeFileSync(p, data);
  return p;
}

function run(args) {
  const r = spawnSync(bake, args, { encoding: 'utf8', timeout: 60000, maxBuffer: 64 << 20 });
  if (r.error) throw new Error(`cannot run ${bake}: ${r.error.message}`);
  return { code: r.status, signal: r.signal, stdout: r.stdout, stderr: r.stderr, args };
}

const show = (r) => `prt-bake ${r.args.map((a) => JSON.stringify(a)).join(' ')}`;
const detail = (r) => `exit ${r.code}${r.signal ? ` (signal ${r.signal})` : ''}, stderr: ${JSON.stringify(r.stderr.trim())}`;

// Runs and expects `code`; on failure, stderr must be exactly "prt-bake: error: ..." lines
// matching `pattern` (a RegExp) and stdout must stay empty.
function expectExit(args, code, pattern) {
  const r = run(args);
  if (!check(r.code === code, `${show(r)}: expected exit ${code}, got ${detail(r)}`)) return r;
  if (code !== 0) {
    check(/^prt-bake: error: /.test(r.stderr), `${show(r)}: stderr should start with "prt-bake: error: ", got ${JSON.stringify(r.stderr)}`);
    check(r.stdout === '', `${show(r)}: stdout should be empty on error, got ${JSON.stringify(r.stdout.slice(0, 200))}`);
  }
  if (pattern) check(pattern.test(r.stderr), `${show(r)}: stderr should match ${pattern}, got ${JSON.stringify(r.stderr)}`);
  return r;
}

// Runs `probe ... --json`, expects success, parses and sanity-checks the JSON.
function probeJson(args) {
  const r = expectExit(['probe', ...args, '--json'], 0);
  if (r.code !== 0) return null;
  let j;
  try {
    j = JSON.parse(r.stdout);
  } catch (e) {
    check(false, `${show(r)}: stdout is not JSON (${e.message}): ${r.stdout.slice(0, 300)}`);
    return null;
  }
  const n = j.order * j.order;
  check(Array.isArray(j.coefficients) && j.coefficients.length === n,
        `${show(r)}: expected ${n} coefficient rows, got ${j.coefficients && j.coefficients.length}`);
  check(j.index_convention === 'i = l(l+1)+m', `${show(r)}: index_convention is ${JSON.stringify(j.index_convention)}`);
  for (const [i, row] of (j.coefficients || []).entries()) {
    check(Array.isArray(row) && row.length === 3 && row.every((v) => typeof v === 'number' && Number.isFinite(v)),
          `${show(r)}: coefficient row ${i} is not 3 finite numbers: ${JSON.stringify(row)}`);
  }
  j.stderr = r.stderr;
  j.show = show(r);
  return j;
}

const SQRT_PI = Math.sqrt(Math.PI);
const near = (a, b, tol) => Math.abs(a - b) <= tol;

// Expects c0 = value * 2 sqrt(pi) in every channel and every other coefficient ~ 0: the
// projection of a constant radiance `value` over the whole sphere. Band 1 vanishes by
// symmetry (but see the angular map below); higher bands carry the quadrature error of small images (the
// 64x32 equirect fixtures: about 3e-3 in l = 2, shrinking as 1/height^2), hence `absTol`.
function expectConstant(j, value, relTol, absTol, band1Tol = 1e-5) {
  if (!j) return;
  const want = 2 * SQRT_PI * value;
  j.coefficients[0].forEach((c, ch) =>
    check(near(c, want, relTol * want), `${j.show}: L00[${ch}] = ${c}, expected ${want.toFixed(6)} (+-${relTol * 100}%)`));
  for (let i = 1; i < j.coefficients.length; i++) {
    const tol = i < 4 ? band1Tol * (1 + want) : absTol;
    j.coefficients[i].forEach((c, ch) =>
      check(Math.abs(c) <= tol, `${j.show}: coefficient ${i}[${ch}] = ${c}, expected ~0 (|c| <= ${tol})`));
  }
}

function truncated(src, length, name) {
  const data = fs.readFileSync(src);
  if (!check(length < data.length, `truncation of ${src} to ${length} bytes would not shorten it`)) return null;
  return workFile(name, data.subarray(0, length));
}

// Deterministic PRNG (mulberry32) so every run tests the same bytes.
function rng(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

// Every truncation of `src` at the given byte counts must fail with exit 1 and a message
// naming the file and the problem.
function expectTruncationsFail(src, cuts, kind) {
  const size = fs.statSync(src).size;
  for (const cut of cuts) {
    const length = cut < 0 ? size + cut : cut < 1 ? Math.floor(size * cut) : cut;
    const p = truncated(src, length, `${path.basename(src)}.cut${length}`);
    if (!p) continue;
    const r = expectExit(['probe', p, '--order', '2', '--format', 'equirect'], EXIT_INVALID_INPUT);
    check(r.stderr.includes(p), `${show(r)}: the message should name ${p}: ${JSON.stringify(r.stderr)}`);
    check(/truncated|corrupt|ends early/i.test(r.stderr) && r.stderr.includes(kind),
          `${show(r)}: the message should say the ${kind} file is truncated or corrupt: ${JSON.stringify(r.stderr)}`);
  }
}

const cases = {
  help() {
    let r = expectExit(['--help'], 0);
    check(/Usage: prt-bake/.test(r.stdout) && /prt-bake <command>/.test(r.stdout) && /probe/.test(r.stdout) && /--default -o ASSET/.test(r.stdout) &&
          /info/.test(r.stdout) && /shade/.test(r.stdout), `--help output: ${r.stdout}`);
    expectExit(['-h'], 0);
    r = expectExit(['probe', '--help'], 0);
    for (const flag of ['--order', '--format', '--window', '--window-width', '--builtin', '--json', 'equirect', 'angular', 'cross']) {
      check(r.stdout.includes(flag), `probe --help should mention ${flag}: ${r.stdout}`);
    }
    // Help wins over other arguments, even bad ones.
    expectExit(['probe', '--order', 'abc', '--help'], 0);
    r = expectExit(['--version'], 0);
    check(/^prt-bake \d+\.\d+\.\d+\n$/.test(r.stdout), `--version output: ${JSON.stringify(r.stdout)}`);
    // Both help pages list every exit status the tool returns.
    for (const args of [['--help'], ['--default', '--help']]) {
      r = expectExit(args, 0);
      for (const status of [0, 2, 3, 4, 5, 6, 7]) {
        check(new RegExp(`^  ${status}  \\S`, 'm').test(r.stdout), `${show(r)} should list exit status ${status}: ${r.stdout}`);
      }
    }
    // Standard output on a full disk (/dev/full: every write fails with ENOSPC) is an error,
    // not a success: exit 6 (out of disk space), and the message says why.
    const full = fs.openSync('/dev/full', 'w');
    const f = spawnSync(bake, ['--help'], { encoding: 'utf8', stdio: ['ignore', full, 'pipe'] });
    fs.closeSync(full);
    check(f.status === EXIT_RESOURCE_EXHAUSTED && /cannot write to standard output: No space left on device/.test(f.stderr),
          `prt-bake --help > /dev/full: expected exit ${EXIT_RESOURCE_EXHAUSTED} and a message, got exit ${f.status}, stderr ${JSON.stringify(f.stderr)}`);
  },

  usage_errors() {
    const sky = ['probe', '--builtin', 'sky'];
    const cases2 = [
      [[], /missing command/],
      [['frobnicate'], /unknown command 'frobnicate'/],
      [['--bogus'], /unknown option '--bogus'/],
      [[...sky, '--order', '3', '--bogus'], /unknown option '--bogus'/],
      [[...sky, '--order', '3', '-x'], /unknown option '-x'/],
      [[...sky, '--order'], /--order needs a value/],
      [[...sky, '--order', '--json'], /--order needs a value/],
      [[...sky, '--order='], /--order needs a value/],
      [[...sky, '--order', 'abc'], /--order expects an integer in \[1, 16\], got 'abc'/],
      [[...sky, '--order', '3x'], /--order expects an integer in \[1, 16\], got '3x'/],
      [[...sky, '--order', '3.0'], /--order expects an integer in \[1, 16\], got '3.0'/],
      [[...sky, '--order', ' 3'], /--order expects an integer/],
      [[...sky, '--order', ''], /--order expects an integer/],
      [[...sky, '--order', '0'], /--order '0' is out of range; expected an integer in \[1, 16\]/],
      [[...sky, '--order', '99'], /--order '99' is out of range; expected an integer in \[1, 16\]/],
      [[...sky, '--order', '-1'], /--order '-1' is out of range/],
      [[...sky, '--order', '99999999999999999999999'], /out of range/],
      [[...sky, '--order', '3', '--order', '4'], /--order given more than once/],
      [sky, /missing --order/],
      [[...sky, '--order', '3', '--format', 'fisheye'], /unknown --format 'fisheye' \(expected equirect, angular or cross\)/],
      [[...sky, '--order', '3', '--format', 'angular'], /does not apply to --builtin/],
      [[...sky, '--order', '3', '--window', 'kaiser'], /unknown window 'kaiser'/],
      [[...sky, '--order', '3', '--window', 'hanning', '--window-width', 'wide'], /--window-width expects a number in \[0, 1000\], got 'wide'/],
      [[...sky, '--order', '3', '--window', 'hanning', '--window-width', '-1'], /--window-width '-1' is out of range/],
      [[...sky, '--order', '3', '--window', 'hanning', '--window-width', 'nan'], /--window-width expects a number/],
      [[...sky, '--order', '3', '--window', 'hanning', '--window-width', 'inf'], /--window-width expects a number/],
      [[...sky, '--order', '3', '--window', 'hanning', '--window-width', '2.5e'], /--window-width expects a number/],
      [[...sky, '--order', '3', '--window-width', '2'], /--window-width needs --window/],
      [[...sky, '--order', '3', '--json=yes'], /--json takes no value/],
      [['probe', '--order', '3'], /missing IMAGE/],
      [['probe', 'a.exr', 'b.exr', '--order', '3'], /expected one IMAGE, got 2/],
      [['probe', 'a.exr', '--builtin', 'sky', '--order', '3'], /either IMAGE or --builtin/],
      [['probe', '--builtin', 'moon', '--order', '3'], /unknown --builtin 'moon'/],
    ];
    for (const [args, pattern] of cases2) expectExit(args, EXIT_USAGE, pattern);
    // "--" ends the options: a file named "--json" is an IMAGE, here a missing one (exit 1).
    expectExit(['probe', '--order', '2', '--', '--json'], EXIT_NOT_FOUND, /'--json': no such file/);
    // Valid spellings.
    expectExit([...sky, '--order=2', '--window=lanczos', '--window-width=1.5e0'], 0);
  },

  builtin_sky() {
    const j = probeJson(['--builtin', 'sky', '--order', '4']);
    if (!j) return;
    check(j.source === 'builtin:sky' && j.format === 'equirect' && j.width === 256 && j.height === 128 &&
          j.order === 4 && j.window === 'none', `${j.show}: header fields: ${JSON.stringify({ ...j, coefficients: undefined })}`);
    const c = j.coefficients;
    const [r, g, b] = c[0];
    check(r > 0 && g > 0 && b > 0, `${j.show}: L00 should be positive in every channel: ${c[0]}`);
    check(b > r, `${j.show}: a blue sky should have L00 blue > red: ${c[0]}`);
    // Band 1: i = 1 is y(1,-1) ~ y (up), i = 2 is y(1,0) ~ z, i = 3 is y(1,1) ~ x.
    // builtin_environment.h puts the sun at elevation 35, azimuth -50 degrees (from +x
    // toward +z): up, toward +x and -z. Sky and ground depend on height only, so the x and z
    // coefficients come from the sun alone and point at its azimuth.
    const wantAz = -50;
    for (let ch = 0; ch < 3; ch++) {
      check(c[1][ch] > 0, `${j.show}: channel ${ch}: L1,-1 (y) = ${c[1][ch]} should be > 0 (sun and sky above)`);
      check(c[2][ch] < 0, `${j.show}: channel ${ch}: L1,0 (z) = ${c[2][ch]} should be < 0 (sun toward -z)`);
      check(c[3][ch] > 0, `${j.show}: channel ${ch}: L1,1 (x) = ${c[3][ch]} should be > 0 (sun toward +x)`);
      const az = (Math.atan2(c[2][ch], c[3][ch]) * 180) / Math.PI;
      check(Math.abs(az - wantAz) < 1, `${j.show}: channel ${ch}: band-1 azimuth ${az.toFixed(2)} deg, sun is at ${wantAz}`);
    }
    // Windowing keeps L00 and damps the higher bands.
    const w = probeJson(['--builtin', 'sky', '--order', '4', '--window', 'hanning']);
    if (w) {
      check(w.window === 'hanning' && w.window_width === 4, `${w.show}: window fields ${w.window} ${w.window_width}`);
      check(near(w.coefficients[0][0], c[0][0], 1e-6 * Math.abs(c[0][0])), `${w.show}: window changed L00`);
      // Hanning with W = 4: w_1 = (1 + cos(pi/4)) / 2.
      const w1 = (1 + Math.cos(Math.PI / 4)) / 2;
      check(near(w.coefficients[3][0], c[3][0] * w1, 1e-5 * Math.abs(c[3][0]) + 1e-7),
            `${w.show}: L1,1 = ${w.coefficients[3][0]}, expected ${c[3][0] * w1}`);
    }
  },

  table_output() {
    const r = expectExit(['probe', '--builtin', 'sky', '--order', '3'], 0);
    const lines = r.stdout.trim().split('\n');
    const rows = lines.filter((l) => /^\s*\d+\s+\d+\s+-?\d+\s/.test(l));
    check(rows.length === 9, `table should have 9 coefficient rows, got ${rows.length}:\n${r.stdout}`);
    check(/source: builtin:sky/.test(r.stdout) && /equirect/.test(r.stdout), `table header: ${r.stdout}`);
    const j = probeJson(['--builtin', 'sky', '--order', '3']);
    rows.forEach((line, i) => {
      const [idx, l, m, ...rgb] = line.trim().split(/\s+/).map(Number);
      check(idx === i && l === Math.floor(Math.sqrt(i)) && m === i - l * (l + 1), `table row ${i} index/l/m: ${line}`);
      if (j) rgb.forEach((v, ch) => check(near(v, j.coefficients[i][ch], 1e-6 * Math.abs(v) + 1e-9), `table row ${i} disagrees with JSON: ${line}`));
    });
  },

  missing_file() {
    const missing = path.join(workDir, 'no', 'such', 'env.exr');
    let r = expectExit(['probe', missing, '--order', '3'], EXIT_NOT_FOUND, /no such file/);
    check(r.stderr.includes(missing), `${show(r)}: message should name the path: ${r.stderr}`);
    r = expectExit(['probe', workDir, '--order', '3'], EXIT_INVALID_INPUT, /is a directory/);
    // A FIFO is refused at once, not waited on.
    const fifo = workFile('env.fifo', '');
    fs.rmSync(fifo);
    check(spawnSync('mkfifo', [fifo]).status === 0, 'mkfifo failed');
    expectExit(['probe', fifo, '--order', '3'], EXIT_INVALID_INPUT, /env\.fifo': not a regular file/);
    check(r.stderr.includes(workDir), `${show(r)}: message should name the path`);
    if (process.getuid && process.getuid() !== 0) {  // root reads anything
      const p = workFile('unreadable.exr', fs.readFileSync(fixture('const1_zip.exr')));
      fs.chmodSync(p, 0);
      expectExit(['probe', p, '--order', '3'], EXIT_NOT_FOUND, /cannot open: Permission denied/);
    }
  },

  unknown_format() {
    const next = rng(12345);
    const bytes = Buffer.alloc(4096, 0).map(() => Math.floor(next() * 256));
    bytes[0] = 0x42;  // not the first byte of any recognised signature
    for (const name of ['random.bin', 'random.exr', 'random.png']) {
      const p = workFile(name, bytes);
      const r = expectExit(['probe', p, '--order', '3'], EXIT_INVALID_INPUT, /unknown image format/);
      check(r.stderr.includes(p), `${show(r)}: message should name the path`);
    }
    expectExit(['probe', workFile('text.hdr', 'hello, world\n'), '--order', '3'], EXIT_INVALID_INPUT, /unknown image format/);
    expectExit(['probe', workFile('empty.exr', ''), '--order', '3'], EXIT_INVALID_INPUT, /file is empty/);
    // Content, not the extension, picks the decoder.
    const p = workFile('png_named.exr', fs.readFileSync(fixture('const1.png')));
    expectConstant(probeJson([p, '--order', '2']), 1, 1e-4, 4e-3);
  },

  truncated_png() {
    probeJson([fixture('noise.png'), '--order', '2']);  // the untruncated file is fine
    expectTruncationsFail(fixture('noise.png'), [0.5, 0.9, -1, -12, 33, 20, 8], 'PNG');
  },

  truncated_exr() {
    for (const name of ['noise.exr', 'noise_zip.exr', 'const1_dwab.exr']) {
      probeJson([fixture(name), '--order', '2']);
      expectTruncationsFail(fixture(name), [0.5, 0.9, -1, 40, 4], 'OpenEXR');
    }
  },

  truncated_hdr_jpeg() {
    for (const [name, kind] of [['noise.hdr', 'Radiance HDR'], ['noise.jpg', 'JPEG']]) {
      probeJson([fixture(name), '--order', '2']);
      expectTruncationsFail(fixture(name), [0.5, 0.9, -1, 20], kind);
    }
  },

  constant_radiance() {
    // Radiance 1 everywhere: L00 = 2 sqrt(pi) = 3.5449, the rest 0, in every lossless format.
    for (const name of ['const1_zip.exr', 'const1_piz.exr', 'const1_dwab.exr', 'const1.hdr', 'const1.png']) {
      const j = probeJson([fixture(name), '--order', '4']);
      expectConstant(j, 1, 1e-4, 4e-3);
      if (j) check(j.format === 'equirect' && j.format_guessed === true && /reading it as equirect/.test(j.stderr),
                   `${j.show}: should guess equirect from 2:1 and say so: ${j.format} ${JSON.stringify(j.stderr)}`);
    }
    // sRGB decoding: code 128 is linear 0.2158605 (a plain 2.2 gamma would give 0.2195).
    expectConstant(probeJson([fixture('gray128.png'), '--order', '3']), 0.2158605, 1e-3, 1e-3);
    expectConstant(probeJson([fixture('gray188.jpg'), '--order', '3']), 0.5028886, 1e-2, 2e-3);
  },

  layouts() {
    const angular = probeJson([fixture('const1_angular.exr'), '--order', '3']);
    if (angular) check(angular.format === 'angular' && angular.format_guessed, `${angular.show}: 1:1 should be angular`);
    // The angular map is not symmetric in z (centre +z, rim -z): its band-1 z term carries
    // quadrature error too.
    expectConstant(angular, 1, 5e-3, 5e-3, 1e-3);
    for (const name of ['const1_cross.exr', 'const1_vcross.png']) {
      const j = probeJson([fixture(name), '--order', '3']);
      if (j) check(j.format === 'cross' && j.format_guessed, `${j.show}: 4:3 and 3:4 should be cross`);
      expectConstant(j, 1, 1e-4, 1e-4);
    }
    // An explicit --format wins over the guess and says nothing about guessing.
    const j = probeJson([fixture('const1_cross.exr'), '--order', '2', '--format', 'equirect']);
    if (j) check(j.format === 'equirect' && j.format_guessed === false && /not 2:1/.test(j.stderr),
                 `${j.show}: explicit equirect on 4:3: ${j.format} ${JSON.stringify(j.stderr)}`);
    expectExit(['probe', fixture('const1_zip.exr'), '--order', '2', '--format', 'angular'], EXIT_INVALID_INPUT, /must be square/);
    expectExit(['probe', fixture('const1_zip.exr'), '--order', '2', '--format', 'cross'], EXIT_INVALID_INPUT, /4:3/);
    // No layout fits 5:3: the error asks for --format, which then works.
    expectExit(['probe', fixture('odd_aspect.png'), '--order', '2'], EXIT_INVALID_INPUT, /50x30: cannot guess its layout.*pass --format/);
    probeJson([fixture('odd_aspect.png'), '--order', '2', '--format', 'equirect']);
  },

  orientation() {
    // Radiance 1 above the horizon only: row 0 must be the top of the image in every
    // loader. L00 = sqrt(pi), L1,-1 (y) = sqrt(3 pi)/2, x and z terms 0.
    for (const name of ['top_bright.exr', 'top_bright.png', 'top_bright.hdr']) {
      const j = probeJson([fixture(name), '--order', '2']);
      if (!j) continue;
      for (let ch = 0; ch < 3; ch++) {
        const [c0, c1, c2, c3] = j.coefficients.map((row) => row[ch]);
        check(near(c0, SQRT_PI, 1e-3), `${j.show}: L00 = ${c0}, expected ${SQRT_PI}`);
        check(near(c1, Math.sqrt(3 * Math.PI) / 2, 5e-3), `${j.show}: L1,-1 = ${c1}, expected ${Math.sqrt(3 * Math.PI) / 2} (image upside down?)`);
        check(Math.abs(c2) < 1e-4 && Math.abs(c3) < 1e-4, `${j.show}: L1,0 = ${c2}, L1,1 = ${c3}, expected 0`);
      }
    }
  },

  bad_content() {
    expectExit(['probe', fixture('nan.exr'), '--order', '2'], EXIT_INVALID_INPUT, /nan\.exr': image has a non-finite value at pixel \(5, 7\)/);
    expectExit(['probe', fixture('wide.exr'), '--order', '2'], EXIT_INVALID_INPUT, /image is too large \(40000x2\); each side must be at most 32768/);
    expectExit(['probe', fixture('wide.png'), '--order', '2'], EXIT_INVALID_INPUT, /image is too large \(40000x1\); each side must be at most 32768/);
    expectExit(['probe', fixture('zero.png'), '--order', '2'], EXIT_INVALID_INPUT, /zero\.png'.*(0-pixel|zero size)/);
    // An EXR signature followed by garbage reaches OpenEXR, whose exception becomes a message.
    const next = rng(7);
    const junk = Buffer.alloc(2048, 0).map(() => Math.floor(next() * 256));
    junk.set([0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0]);
    expectExit(['probe', workFile('junk.exr', junk), '--order', '2'], EXIT_INVALID_INPUT, /junk\.exr': cannot read OpenEXR data/);
  },

  blender_exr() {
    if (!check(fs.existsSync(blenderDir),
               `${blenderDir} does not exist: the blender-data package is not installed ` +
               `(apt-get install --no-install-recommends blender-data); this test needs its CC0 EXRs`)) return;
    const files = fs.readdirSync(blenderDir).filter((f) => f.endsWith('.exr')).sort();
    if (!check(files.length > 0, `${blenderDir} holds no .exr files`)) return;
    for (const f of files) {
      const j = probeJson([path.join(blenderDir, f), '--order', '3']);
      if (!j) continue;
      check(j.format === 'equirect' && j.width === 2 * j.height, `${j.show}: expected a 2:1 equirect, got ${j.format} ${j.width}x${j.height}`);
      check(j.coefficients[0].every((v) => v > 0), `${j.show}: L00 should be positive in every channel: ${j.coefficients[0]}`);
    }
  },

  fuzz() {
    // Mutated copies of valid files: whatever the bytes, prt-bake must exit 0 with valid JSON
    // or 1 with an error naming the file; never crash, hang or exit otherwise.
    // PRT_FUZZ_ITERATIONS and PRT_FUZZ_SEED widen the search by hand.
    const seeds = ['noise.exr', 'noise_zip.exr', 'const1_dwab.exr', 'const1_piz.exr', 'noise.png', 'noise.hdr', 'noise.jpg'];
    const iterations = Number(process.env.PRT_FUZZ_ITERATIONS || 350);
    const next = rng(Number(process.env.PRT_FUZZ_SEED || 2024));
    const pick = (n) => Math.floor(next() * n);
    let ok = 0, rejected = 0;
    for (let k = 0; k < iterations; k++) {
      const src = fs.readFileSync(fixture(seeds[k % seeds.length]));
      let data = Buffer.from(src);
      const kind = pick(3);
      if (kind === 0) {
        for (let n = 1 + pick(8); n > 0; n--) data[pick(data.length)] = pick(256);  // byte flips
      } else if (kind === 1) {
        const at = pick(data.length), len = 1 + pick(64);  // a run of random bytes
        for (let i = at; i < Math.min(data.length, at + len); i++) data[i] = pick(256);
      } else {
        data = data.subarray(0, pick(data.length));  // truncation
        if (data.length > 4) data[4 + pick(data.length - 4)] = pick(256);
      }
      const p = workFile(`fuzz${k}_${seeds[k % seeds.length]}`, data);
      const r = run(['probe', p, '--order', '3', '--format', 'equirect', '--json']);
      if (r.code === 0) {
        ok++;
        let j = null;
        try { j = JSON.parse(r.stdout); } catch { /* reported below */ }
        check(j && j.coefficients.length === 9 && j.coefficients.flat().every(Number.isFinite),
              `${show(r)}: exit 0 but bad JSON: ${r.stdout.slice(0, 200)}`);
      } else if (check(r.code === EXIT_INVALID_INPUT, `${show(r)}: expected exit 0 or ${EXIT_INVALID_INPUT}, got ${detail(r)}`)) {
        rejected++;
        check(r.stderr.includes(`prt-bake: error: '${p}'`), `${show(r)}: the error should start by naming the file: ${r.stderr}`);
      }
      fs.rmSync(p);
    }
    console.log(`fuzz: ${ok} mutated files decoded, ${rejected} rejected cleanly`);
  },
};

if (!cases[caseName]) {
  console.error(`unknown case '${caseName}'; known: ${Object.keys(cases).join(', ')}`);
  process.exit(2);
}
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });
try {
  cases[caseName]();
} catch (e) {
  failures.push(`exception: ${e.stack || e}`);
}
if (failures.length) {
  console.error(`${caseName}: ${failures.length} of ${checks} checks failed:`);
  for (const f of failures) console.error(`  FAIL ${f}`);
  process.exit(1);
}
console.log(`${caseName}: all ${checks} checks passed`);
