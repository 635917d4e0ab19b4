// What the 3D model viewer (assets/js/model-viewer.js) uses of three and urdf-loader: the
// entry of the bundle tools/bundle-model-viewer.mjs makes, so that the reader's browser
// loads one minified file holding these and what they need, and nothing else of three.
export {
  Box3,
  Color,
  DirectionalLight,
  GridHelper,
  HemisphereLight,
  LoadingManager,
  PerspectiveCamera,
  Scene,
  Vector3,
  WebGLRenderer,
} from "three";
export { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
export { default as URDFLoader } from "urdf-loader";
