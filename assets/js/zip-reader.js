// The files of a .zip the reader dropped on "Your own model" (assets/js/own-model.js), read
// in the browser: the central directory at the end of the archive names each file, its
// method (0 stored, 8 deflated) and where its data is; deflated data goes through the
// browser's own DecompressionStream. Nothing leaves the reader's machine.

const END_OF_DIRECTORY = 0x06054b50;
const DIRECTORY_ENTRY = 0x02014b50;
const LOCAL_HEADER = 0x04034b50;

async function inflate(bytes) {
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate-raw"));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

// {path: ArrayBuffer} of every file in `buffer` (an ArrayBuffer of a zip); `name` is the
// archive's name for the messages.
export async function readZip(buffer, name) {
  const view = new DataView(buffer);
  let end = -1;
  for (let at = buffer.byteLength - 22; at >= Math.max(0, buffer.byteLength - 65557); at--) {
    if (view.getUint32(at, true) === END_OF_DIRECTORY) { end = at; break; }
  }
  if (end < 0) throw new Error(`${name} is not a zip archive (no central directory found).`);
  const count = view.getUint16(end + 10, true);
  let at = view.getUint32(end + 16, true);
  const decoder = new TextDecoder();
  const files = {};
  for (let i = 0; i < count; i++) {
    if (view.getUint32(at, true) !== DIRECTORY_ENTRY) throw new Error(`${name}: a damaged zip archive.`);
    const method = view.getUint16(at + 10, true);
    const size = view.getUint32(at + 20, true);
    const nameLength = view.getUint16(at + 28, true);
    const extraLength = view.getUint16(at + 30, true);
    const commentLength = view.getUint16(at + 32, true);
    const local = view.getUint32(at + 42, true);
    const path = decoder.decode(new Uint8Array(buffer, at + 46, nameLength)).replaceAll("\\", "/");
    at += 46 + nameLength + extraLength + commentLength;
    if (path.endsWith("/")) continue;   // a folder
    if (view.getUint32(local, true) !== LOCAL_HEADER) throw new Error(`${name}: a damaged zip archive.`);
    const start = local + 30 + view.getUint16(local + 26, true) + view.getUint16(local + 28, true);
    const stored = new Uint8Array(buffer, start, size);
    if (method === 0) files[path] = stored.slice().buffer;
    else if (method === 8) files[path] = (await inflate(stored)).buffer;
    else throw new Error(`${name}/${path}: compressed with method ${method}, which the browser `
      + "cannot unpack; zip the folder again with your system's own zip (deflate).");
  }
  return files;
}
