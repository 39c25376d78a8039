package org.palp.bridge;

import java.io.IOException;
import java.net.InetAddress;

/**
 * The bridge core with a SimulatedArm on a loopback ephemeral port, for the test of
 * bridge_check.py and the SDK interop test. Prints "port N", cycles every 5 ms, and ends when
 * standard input closes (with --ignore-stdin: when killed), after 60 s at the latest.
 */
public final class LoopbackBridge {
  private LoopbackBridge() {}

  public static void main(String[] args) throws IOException, InterruptedException {
    RegisterStore store = new RegisterStore();
    final BridgeCore core = new BridgeCore(store, new SimulatedArm(300000, 310000), Clock.SYSTEM);
    ModbusTcpServer server = new ModbusTcpServer(store, core, new ModbusTcpServer.Log() {
      @Override
      public void info(String message) {
        System.err.println(message);
      }
    }, InetAddress.getByName("127.0.0.1"), 0, 10000);
    System.out.println("port " + server.port());
    System.out.flush();
    final boolean[] done = {false};
    Thread stdin = new Thread(new Runnable() {
      @Override
      public void run() {
        try {
          while (System.in.read() >= 0) {
            // until the test closes it
          }
        } catch (IOException e) {
          // closed
        }
        synchronized (done) {
          done[0] = true;
        }
      }
    });
    stdin.setDaemon(true);
    if (!(args.length > 0 && args[0].equals("--ignore-stdin"))) stdin.start();
    long end = System.nanoTime() / 1000000L + 60000L;
    while (System.nanoTime() / 1000000L < end) {
      synchronized (done) {
        if (done[0]) break;
      }
      core.cycle();
      Thread.sleep(5);
    }
    server.close();
  }
}
