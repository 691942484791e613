// A zip archive of a few small text files, stored as they are (no compression): what a
// FreeCAD tool library needs to leave the page as one download, its library and its bits in
// the folders FreeCAD keeps them in. The layout follows PKWARE's APPNOTE (4.3.7 local file
// header, 4.3.12 central directory header, 4.3.16 end of central directory record), with
// UTF-8 names (flag bit 11) and the CRC-32 of ISO 3309.

const CRC = new Uint32Array(256).map((_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});

function crc32(bytes) {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

// `files` ([{ name, text }], names with `/` between folders) as the bytes of a zip archive.
export function zipStored(files, when = new Date()) {
  const utf8 = new TextEncoder();
  // MS-DOS time and date, as the headers keep them.
  const time = (when.getHours() << 11) | (when.getMinutes() << 5) | (when.getSeconds() >> 1);
  const date = ((Math.max(when.getFullYear(), 1980) - 1980) << 9) | ((when.getMonth() + 1) << 5) | when.getDate();
  const parts = [], central = [];
  let offset = 0;
  for (const f of files) {
    const name = utf8.encode(f.name), data = utf8.encode(f.text), crc = crc32(data);
    // Version needed 2.0, UTF-8 names, stored, the time, CRC and both sizes alike.
    const head = (signature, extra) => {
      const h = new DataView(new ArrayBuffer(extra + 26));
      h.setUint32(0, signature, true);
      let at = 4;
      if (extra === 20) { h.setUint16(at, 20, true); at += 2; }
      for (const [v, size] of [[20, 2], [0x0800, 2], [0, 2], [time, 2], [date, 2], [crc, 4], [data.length, 4], [data.length, 4], [name.length, 2], [0, 2]]) {
        if (size === 2) h.setUint16(at, v, true); else h.setUint32(at, v, true);
        at += size;
      }
      return h;
    };
    const local = head(0x04034b50, 4);
    const dir = head(0x02014b50, 20);
    // Comment length, disk, internal and external attributes, and where its local header is.
    dir.setUint16(32, 0, true); dir.setUint16(34, 0, true); dir.setUint16(36, 0, true); dir.setUint32(38, 0, true); dir.setUint32(42, offset, true);
    parts.push(new Uint8Array(local.buffer), name, data);
    central.push(new Uint8Array(dir.buffer), name);
    offset += local.byteLength + name.length + data.length;
  }
  const size = central.reduce((n, p) => n + p.length, 0);
  const end = new DataView(new ArrayBuffer(22));
  end.setUint32(0, 0x06054b50, true);
  end.setUint16(8, files.length, true); end.setUint16(10, files.length, true);
  end.setUint32(12, size, true); end.setUint32(16, offset, true);
  const all = [...parts, ...central, new Uint8Array(end.buffer)];
  const out = new Uint8Array(all.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const p of all) { out.set(p, at); at += p.length; }
  return out;
}
