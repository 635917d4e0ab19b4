// What the 3D model viewer (assets/js/model-viewer.js) uses of three and urdf-loader: the
// entry of the bundle tools/bundle-model-viewer.mjs makes, so that the reader's browser
// loads one minified file holding these and what they need, and nothing else of three.
// "Your own model" (assets/js/own-model.js) draws MuJoCo's own shapes with the same file:
// the geometries, meshes and matrices below, most of which urdf-loader needs anyway.
export {
  Box3,
  BoxGeometry,
  BufferAttribute,
  BufferGeometry,
  CapsuleGeometry,
  Color,
  CylinderGeometry,
  DirectionalLight,
  GridHelper,
  Group,
  HemisphereLight,
  LoadingManager,
  Matrix4,
  Mesh,
  MeshPhongMaterial,
  PerspectiveCamera,
  Scene,
  SphereGeometry,
  Vector3,
  WebGLRenderer,
} from "three";
export { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
export { default as URDFLoader } from "urdf-loader";
