// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

import static org.junit.Assert.assertArrayEquals;
import static org.junit.Assert.assertEquals;
import static org.junit.Assert.assertTrue;
import static org.junit.Assert.fail;

import java.io.DataInputStream;
import java.io.IOException;
import java.net.ConnectException;
import java.net.InetAddress;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Random;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import org.junit.After;
import org.junit.Before;
import org.junit.Test;
import org.palp.bridge.RegisterMap.CommandCode;
import org.palp.bridge.RegisterMap.HostControl;
import org.palp.bridge.RegisterMap.Result;

/** The Modbus TCP server over a real loopback socket on an ephemeral port. */
public class ModbusTcpServerTest {
  private RegisterStore store;
  private ModbusTcpServer server;
  private final List<String> log = Collections.synchronizedList(new ArrayList<String>());
  private volatile CountDownLatch closed = new CountDownLatch(1);
  private final List<Socket> sockets = new ArrayList<Socket>();

  @Before
  public void setUp() throws IOException {
    store = new RegisterStore();
    start(store, 0);
  }

  private void start(RegisterStore s, int idleTimeoutMs) throws IOException {
    server = new ModbusTcpServer(s, new ModbusTcpServer.Listener() {
      @Override
      public void connectionOpened() {}

      @Override
      public void connectionClosed() {
        closed.countDown();
      }
    }, new ModbusTcpServer.Log() {
      @Override
      public void info(String message) {
        log.add(message);
      }
    }, InetAddress.getLoopbackAddress(), 0, idleTimeoutMs);
  }

  @After
  public void tearDown() throws IOException {
    for (Socket s : sockets) s.close();
    server.close();
  }

  private Socket connect() throws IOException {
    Socket s = new Socket(InetAddress.getLoopbackAddress(), server.port());
    s.setSoTimeout(2000);
    sockets.add(s);
    return s;
  }

  private static byte[] frame(int transaction, int unit, byte[] pdu) {
    byte[] f = new byte[7 + pdu.length];
    f[0] = (byte) (transaction >> 8);
    f[1] = (byte) transaction;
    f[4] = (byte) ((pdu.length + 1) >> 8);
    f[5] = (byte) (pdu.length + 1);
    f[6] = (byte) unit;
    System.arraycopy(pdu, 0, f, 7, pdu.length);
    return f;
  }

  /** Sends one request and returns the response PDU, checking the MBAP header echoes ours. */
  private static byte[] request(Socket s, int transaction, byte[] pdu) throws IOException {
    s.getOutputStream().write(frame(transaction, 1, pdu));
    DataInputStream in = new DataInputStream(s.getInputStream());
    byte[] header = new byte[7];
    in.readFully(header);
    assertEquals("transaction id", transaction, ((header[0] & 0xFF) << 8) | (header[1] & 0xFF));
    assertEquals("protocol id", 0, header[2] | header[3]);
    assertEquals("unit id", 1, header[6]);
    byte[] reply = new byte[(((header[4] & 0xFF) << 8) | (header[5] & 0xFF)) - 1];
    in.readFully(reply);
    return reply;
  }

  private static byte[] bytes(int... v) {
    byte[] b = new byte[v.length];
    for (int i = 0; i < v.length; ++i) b[i] = (byte) v[i];
    return b;
  }

  private static byte[] read(int address, int count) {
    return bytes(3, address >> 8, address, count >> 8, count);
  }

  private static byte[] writeMany(int address, int[] regs) {
    byte[] b = new byte[6 + 2 * regs.length];
    b[0] = 16;
    b[1] = (byte) (address >> 8);
    b[2] = (byte) address;
    b[3] = (byte) (regs.length >> 8);
    b[4] = (byte) regs.length;
    b[5] = (byte) (2 * regs.length);
    for (int i = 0; i < regs.length; ++i) {
      b[6 + 2 * i] = (byte) (regs[i] >> 8);
      b[7 + 2 * i] = (byte) regs[i];
    }
    return b;
  }

  private static void assertClosedByServer(Socket s) throws IOException {
    try {
      assertEquals("the server closes the connection", -1, s.getInputStream().read());
    } catch (SocketTimeoutException e) {
      fail("the server kept the connection open");
    } catch (IOException e) {
      // a reset is a close too
    }
  }

  @Test
  public void readsTheIdentificationBlockEchoingTransactionAndUnit() throws IOException {
    byte[] reply = request(connect(), 0xBEEF, read(0, 10));
    assertArrayEquals(bytes(3, 20, 0x50, 0x41, 0x4c, 0x50, 0, 1, 0, 0, 0, 100, 0, 53, 0, 200, 0, 3, 1, 0x2c, 0, 24),
        reply);
  }

  @Test
  public void unknownFunctionIsException01() throws IOException {
    Socket s = connect();
    assertArrayEquals(bytes(0x84, 1), request(s, 1, bytes(4, 0, 0, 0, 1)));
    assertArrayEquals(bytes(0x81, 1), request(s, 2, bytes(1)));
  }

  @Test
  public void addressesOutsideOneBlockAndWritesToReadOnlyBlocksAreException02() throws IOException {
    Socket s = connect();
    assertArrayEquals("across status/gap", bytes(0x83, 2), request(s, 1, read(150, 4)));
    assertArrayEquals("outside every block", bytes(0x83, 2), request(s, 2, read(400, 1)));
    assertArrayEquals("gap after identification", bytes(0x83, 2), request(s, 3, read(10, 1)));
    assertArrayEquals("write to the status block", bytes(0x90, 2), request(s, 4, writeMany(100, new int[] {1})));
    assertArrayEquals("FC6 to identification", bytes(0x86, 2), request(s, 5, bytes(6, 0, 2, 0, 9)));
    assertArrayEquals("part of the command block", bytes(0x90, 2),
        request(s, 6, writeMany(300, new int[RegisterMap.Command.LENGTH - 1])));
    assertArrayEquals("FC6 to the command block", bytes(0x86, 2), request(s, 7, bytes(6, 1, 0x2c, 0, 1)));
    assertArrayEquals("across control and command", bytes(0x90, 2), request(s, 8, writeMany(202, new int[] {500, 1})));
  }

  @Test
  public void badValuesAndCountsAreException03AndChangeNothing() throws IOException {
    Socket s = connect();
    assertArrayEquals("watchdog 99 ms", bytes(0x86, 3), request(s, 1, bytes(6, 0, 202, 0, 99)));
    assertArrayEquals("watchdog 10001 ms", bytes(0x90, 3), request(s, 2, writeMany(200, new int[] {5, 6, 10001})));
    assertArrayEquals(new int[] {0, 0, 500}, store.hostControl());
    byte[] miscounted = writeMany(200, new int[] {5});
    miscounted[5] = 4;
    assertArrayEquals("byte count 4 for 1 register", bytes(0x90, 3), request(s, 3, miscounted));
    assertArrayEquals("read of 0", bytes(0x83, 3), request(s, 4, read(100, 0)));
    assertArrayEquals("read of 126", bytes(0x83, 3), request(s, 5, read(100, 126)));
    assertArrayEquals("short FC3", bytes(0x83, 3), request(s, 6, bytes(3, 0)));
    assertArrayEquals(new int[] {0, 0, 500}, store.hostControl());
  }

  @Test
  public void writesReachTheStoreAndAreEchoed() throws IOException {
    Socket s = connect();
    assertArrayEquals(bytes(6, 0, 200, 0x12, 0x34), request(s, 1, bytes(6, 0, 200, 0x12, 0x34)));
    assertArrayEquals(bytes(16, 0, 201, 0, 2), request(s, 2, writeMany(201, new int[] {3, 1000})));
    assertArrayEquals(new int[] {0x1234, 3, 1000}, store.hostControl());
    int[] command = Blocks.command(9, CommandCode.HOLD).regs();
    assertArrayEquals(bytes(16, 1, 0x2c, 0, 24), request(s, 3, writeMany(300, command)));
    assertArrayEquals(command, store.command());
    byte[] back = request(s, 4, read(HostControl.ADDRESS, 3));
    assertArrayEquals(bytes(3, 6, 0x12, 0x34, 0, 3, 3, 0xe8), back);
  }

  @Test
  public void aSecondClientIsClosedAtOnceAndTheFirstIsStillServed() throws IOException {
    Socket first = connect();
    request(first, 1, read(0, 1));
    Socket second = connect();
    assertClosedByServer(second);
    assertArrayEquals(bytes(3, 2, 0x50, 0x41), request(first, 2, read(0, 1)));
  }

  @Test
  public void malformedFramesCloseTheConnectionAndTheServerServesTheNext() throws IOException, InterruptedException {
    Socket s = connect();
    s.getOutputStream().write(bytes(0, 1, 0, 1, 0, 6, 1, 3, 0, 0, 0, 1));  // protocol id 1
    assertClosedByServer(s);
    assertTrue("closed reported", closed.await(2, TimeUnit.SECONDS));

    closed = new CountDownLatch(1);
    s = connect();
    s.getOutputStream().write(bytes(0, 1, 0, 0, 0, 0, 1));  // length 0
    assertClosedByServer(s);
    assertTrue(closed.await(2, TimeUnit.SECONDS));

    closed = new CountDownLatch(1);
    s = connect();
    s.getOutputStream().write(bytes(0, 1, 0, 0, 0, 6, 1, 3));  // truncated, then the client goes
    s.shutdownOutput();
    assertClosedByServer(s);
    assertTrue(closed.await(2, TimeUnit.SECONDS));

    Random random = new Random(5);
    for (int i = 0; i < 20; ++i) {
      closed = new CountDownLatch(1);
      s = connect();
      byte[] garbage = new byte[1 + random.nextInt(300)];
      random.nextBytes(garbage);
      s.getOutputStream().write(garbage);
      s.shutdownOutput();
      s.setSoTimeout(2000);
      try {
        while (s.getInputStream().read() >= 0) {
          // the server may answer what parsed as requests; it must then close
        }
      } catch (IOException e) {
        // reset: closed too
      }
      assertTrue("garbage " + i + " closed", closed.await(2, TimeUnit.SECONDS));
    }
    assertArrayEquals(bytes(3, 2, 0x50, 0x41), request(connect(), 9, read(0, 1)));
  }

  @Test
  public void aSilentClientIsClosedAfterTheIdleTimeout() throws IOException, InterruptedException {
    server.close();
    start(store, 200);
    Socket s = connect();
    long t0 = System.nanoTime();
    assertClosedByServer(s);
    long ms = (System.nanoTime() - t0) / 1000000L;
    assertTrue("closed after " + ms + " ms", ms >= 150 && ms < 1500);
    assertTrue(closed.await(2, TimeUnit.SECONDS));
  }

  @Test
  public void closeReleasesThePortAndTheClient() throws IOException, InterruptedException {
    Socket s = connect();
    request(s, 1, read(0, 1));
    int port = server.port();
    server.close();
    assertClosedByServer(s);
    assertTrue(closed.await(2, TimeUnit.SECONDS));
    try {
      new Socket(InetAddress.getLoopbackAddress(), port).close();
      fail("port " + port + " still accepts after close()");
    } catch (ConnectException e) {
      // released
    }
  }

  @Test
  public void aCommandOverTheWireIsTakenByTheCycleAndSeenInTheStatus() throws IOException {
    FakeArm arm = new FakeArm();
    FakeClock clock = new FakeClock();
    BridgeCore core = new BridgeCore(store, arm, clock);
    Socket s = connect();
    request(s, 1, bytes(6, 0, 200, 0, 1));
    int[] command = Blocks.command(1, CommandCode.HOLD).regs();
    request(s, 2, writeMany(300, command));
    core.cycle();
    byte[] reply = request(s, 3, read(RegisterMap.StatusBlock.ACK_SEQ, 5));
    // ack_seq 1, ack_result accepted, reject_detail 0, done_seq 1, result done
    assertArrayEquals(bytes(3, 10, 0, 1, 0, Result.ACCEPTED, 0, 0, 0, 1, 0, Result.DONE), reply);
  }
}
