// Issue 52: the Procedures played as a student on the built site, part 2
// of 3 (tests/e2e/procedures.mjs shares the experiments out by weight, so
// the three files, run side by side, take alike).
import { playPart } from "./procedures.mjs";

playPart(1, 3);
