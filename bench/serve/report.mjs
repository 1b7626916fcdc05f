// Turns scripts/bench-serve.sh's raw results (wrk JSON lines, RSS samples) into
// docs/bench/serve.json and docs/bench/serve.md.
// Usage: node report.mjs RAW_DIR OUT_JSON OUT_MD
import fs from 'node:fs';

const [rawDir, outJson, outMd] = process.argv.slice(2);
const read = (name) => fs.readFileSync(`${rawDir}/${name}`, 'utf8');
const wrk = (name) => {
  const line = read(name).split('\n').find((l) => l.startsWith('{'));
  if (!line) throw new Error(`${name}: no wrk JSON line`);
  const r = JSON.parse(line);
  const seconds = r.duration_us / 1e6;
  const errors = Object.values(r.errors).reduce((a, b) => a + b, 0);
  const other = Number(read(name.replace(/\.txt$/, '.other')).trim());
  return { ...r, requests_per_s: r.requests / seconds, mb_per_s: r.bytes / seconds / 1e6, errors_total: errors,
           other_cpu_percent: other };
};
const meta = JSON.parse(read('meta.json'));
const cases = [
  { id: 'asset', what: `${(meta.asset_bytes / 1e6).toFixed(2)} MB asset` },
  { id: 'catalogue', what: `catalogue JSON (${meta.catalogue_bytes} B)` },
];
const results = cases.map((c) => {
  const prt = wrk(`prt-${c.id}.txt`);
  const ngx = wrk(`nginx-${c.id}.txt`);
  return { case: c.id, what: c.what, prt_serve: prt, nginx: ngx, ratio: prt.requests_per_s / ngx.requests_per_s };
});
const rss = read('rss.txt').trim().split('\n').map((l) => {
  const [t, kb] = l.split(/\s+/).map(Number);
  return { t_s: t, rss_kib: kb };
});
const steady = rss.filter((s) => s.t_s >= 5);
const first = steady[0]?.rss_kib ?? 0;
const last = steady[steady.length - 1]?.rss_kib ?? 0;
const max = Math.max(...rss.map((s) => s.rss_kib));
const soak = {
  seconds: meta.soak_seconds,
  wrk: wrk('soak.txt'),
  rss_start_kib: rss[0]?.rss_kib ?? 0,
  rss_at_5s_kib: first,
  rss_end_kib: last,
  rss_max_kib: max,
  growth_after_5s_kib: last - first,
  samples: rss,
};
const doc = { date: meta.date, machine: meta.machine, tools: meta.tools, settings: meta.settings, results, soak };
fs.writeFileSync(outJson, JSON.stringify(doc, null, 2) + '\n');

const f0 = (x) => Math.round(x).toLocaleString('en-US');
const ms = (us) => (us / 1000).toFixed(2);
let md = `# prt-serve against nginx (wrk, loopback)\n\n`;
md += `Run ${meta.date} on ${meta.machine.cpu} (${meta.machine.cores} cores), ${meta.machine.kernel}; `;
md += `${meta.tools.wrk}, ${meta.tools.nginx}. Written by \`scripts/bench-serve.sh\`; raw numbers in `;
md += `[serve.json](serve.json).\n\n`;
md += `${meta.settings.connections} connections, ${meta.settings.wrk_threads} wrk threads, `;
md += `${meta.settings.seconds} s per run; prt-serve ${meta.settings.prt_serve}, nginx ${meta.settings.nginx}. `;
md += `Both serve the same files from the same directory; no Accept-Encoding (identity bodies). `;
md += `wrk, the server and anything else running share the machine's cores, so the ratio `;
md += `(same machine, back to back) is the number to read, not the absolute rates. "Other CPU" is the share `;
md += `of the machine's CPU time used during the run by neither the server nor wrk (other builds, tests).\n\n`;
md += `| what | server | requests/s | ratio to nginx | MB/s | p50 ms | p99 ms | max ms | errors | other CPU |\n`;
md += `|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n`;
for (const r of results) {
  for (const [name, x] of [['prt-serve', r.prt_serve], ['nginx', r.nginx]]) {
    md += `| ${r.what} | ${name} | ${f0(x.requests_per_s)} | ${name === 'prt-serve' ? r.ratio.toFixed(2) + 'x' : '1.00x'} | `;
    md += `${f0(x.mb_per_s)} | ${ms(x.latency_us.p50)} | ${ms(x.latency_us.p99)} | ${ms(x.latency_us.max)} | ${x.errors_total} | `;
    md += `${x.other_cpu_percent.toFixed(1)}% |\n`;
  }
}
md += `\n## Soak: resident memory over ${soak.seconds} s of load\n\n`;
md += `prt-serve serving the asset to ${meta.settings.connections} connections for ${soak.seconds} s `;
md += `(${f0(soak.wrk.requests_per_s)} requests/s, ${soak.wrk.errors_total} errors, other processes `;
md += `${soak.wrk.other_cpu_percent.toFixed(1)}% of the CPU), RSS sampled every `;
md += `${meta.settings.rss_interval_s} s: ${(soak.rss_start_kib / 1024).toFixed(1)} MiB before the load, `;
md += `${(soak.rss_at_5s_kib / 1024).toFixed(1)} MiB after 5 s, ${(soak.rss_end_kib / 1024).toFixed(1)} MiB at the end `;
md += `(max ${(soak.rss_max_kib / 1024).toFixed(1)} MiB; growth after warm-up ${soak.growth_after_5s_kib} KiB).\n\n`;
md += `| t (s) | ${rss.map((s) => s.t_s).join(' | ')} |\n|---|${rss.map(() => '---:').join('|')}|\n`;
md += `| RSS (MiB) | ${rss.map((s) => (s.rss_kib / 1024).toFixed(1)).join(' | ')} |\n`;
fs.writeFileSync(outMd, md);
console.log(md);
