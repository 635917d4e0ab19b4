// Stands in for three's ColladaLoader in the model viewer's bundle. urdf-loader imports it
// for .dae meshes, but the exporter writes STL, so the viewer leaves out its 110 kB: a
// .dae mesh is reported as a failed file, and the page shows the still picture instead.
export class ColladaLoader {
  constructor(manager) {
    this.manager = manager;
  }

  load(url, onLoad, onProgress, onError) {
    this.manager.itemStart(url);
    this.manager.itemError(url);
    onError(new Error(`${url}: Collada meshes are not shown here; the exporter writes STL`));
    this.manager.itemEnd(url);
  }
}
