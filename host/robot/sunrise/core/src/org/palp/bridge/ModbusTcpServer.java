// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

import java.io.DataInputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.net.SocketException;
import java.net.SocketTimeoutException;

/**
 * Modbus TCP server of the bridge (robot-bridge.md sections 2 and 9.3): FC3, FC6 and FC16 over
 * the register store, exceptions 01/02/03/04, ONE client at a time (a second connection is
 * closed at once without an answer). A frame that cannot be parsed (protocol id not 0, length
 * out of range, a truncated frame) closes the connection; a well-framed request that is wrong
 * is answered with an exception. Nothing escapes the accept loop. A client that sends nothing
 * for the idle timeout is closed, so a host that vanished (half-open TCP) never locks out the
 * next one.
 */
public final class ModbusTcpServer {
  /** Told when the client connection opens and closes (the core stops the arm on a close). */
  public interface Listener {
    void connectionOpened();

    void connectionClosed();
  }

  /** Where the server reports what it does (the Sunrise adapter logs it). */
  public interface Log {
    void info(String message);
  }

  private static final int MAX_PDU = 253;

  private final RegisterStore store;
  private final Listener listener;
  private final Log log;
  private final int idleTimeoutMs;
  private final ServerSocket serverSocket;
  private final Thread acceptThread;
  private volatile boolean closing;
  private Socket client;  // guarded by this
  private Thread clientThread;  // guarded by this

  /**
   * Binds port (0: an ephemeral port) on bindAddress (null: every interface) and starts serving.
   * idleTimeoutMs: a connection without a request for this long is closed (0: never).
   */
  public ModbusTcpServer(RegisterStore store, Listener listener, Log log, InetAddress bindAddress, int port,
      int idleTimeoutMs) throws IOException {
    this.store = store;
    this.listener = listener;
    this.log = log;
    this.idleTimeoutMs = idleTimeoutMs;
    serverSocket = new ServerSocket();
    serverSocket.setReuseAddress(true);
    serverSocket.bind(new InetSocketAddress(bindAddress, port), 4);
    acceptThread = new Thread(new Runnable() {
      @Override
      public void run() {
        acceptLoop();
      }
    }, "palp-bridge-accept");
    acceptThread.setDaemon(true);
    acceptThread.start();
    log.info("palp bridge: Modbus TCP server listening on port " + port());
  }

  /** The port the server listens on. */
  public int port() {
    return serverSocket.getLocalPort();
  }

  /** True while a client is connected. */
  public synchronized boolean hasClient() {
    return client != null;
  }

  /** Closes the listening socket and the client connection, and waits for the threads to end. */
  public void close() {
    closing = true;
    closeQuietly(serverSocket);
    Thread t;
    synchronized (this) {
      if (client != null) closeQuietly(client);
      t = clientThread;
    }
    join(acceptThread);
    if (t != null) join(t);
  }

  private void acceptLoop() {
    while (!closing) {
      Socket s;
      try {
        s = serverSocket.accept();
      } catch (IOException e) {
        if (!closing) log.info("palp bridge: accept failed: " + e.getMessage());
        continue;
      }
      try {
        admit(s);
      } catch (RuntimeException e) {
        log.info("palp bridge: dropped a connection: " + e);
        closeQuietly(s);
      }
    }
  }

  private void admit(final Socket s) {
    synchronized (this) {
      if (client != null || closing) {
        log.info("palp bridge: refused a second client from " + s.getRemoteSocketAddress()
            + " (one client at a time)");
        closeQuietly(s);
        return;
      }
      client = s;
      clientThread = new Thread(new Runnable() {
        @Override
        public void run() {
          serve(s);
        }
      }, "palp-bridge-client");
      clientThread.setDaemon(true);
    }
    log.info("palp bridge: client " + s.getRemoteSocketAddress() + " connected");
    listener.connectionOpened();
    clientThread.start();
  }

  private void serve(Socket s) {
    String why = "closed by the client";
    try {
      s.setTcpNoDelay(true);
      s.setKeepAlive(true);
      s.setSoTimeout(idleTimeoutMs);
      DataInputStream in = new DataInputStream(s.getInputStream());
      OutputStream out = s.getOutputStream();
      byte[] header = new byte[7];
      while (!closing) {
        int first = in.read();
        if (first < 0) break;
        header[0] = (byte) first;
        in.readFully(header, 1, 6);
        int protocol = u16(header, 2);
        int length = u16(header, 4);
        if (protocol != 0) {
          why = "protocol identifier " + protocol + " is not Modbus (0)";
          break;
        }
        if (length < 2 || length > MAX_PDU + 1) {
          why = "MBAP length " + length + " outside 2.." + (MAX_PDU + 1);
          break;
        }
        byte[] pdu = new byte[length - 1];
        in.readFully(pdu);
        byte[] reply = handle(pdu);
        byte[] frame = new byte[7 + reply.length];
        System.arraycopy(header, 0, frame, 0, 4);  // transaction and protocol identifiers
        frame[4] = (byte) ((reply.length + 1) >> 8);
        frame[5] = (byte) (reply.length + 1);
        frame[6] = header[6];  // the unit identifier, echoed
        System.arraycopy(reply, 0, frame, 7, reply.length);
        out.write(frame);
        out.flush();
      }
      if (closing) why = "the bridge stops";
    } catch (SocketTimeoutException e) {
      why = "no request for " + idleTimeoutMs + " ms";
    } catch (EOFException e) {
      why = "a truncated frame";
    } catch (SocketException e) {
      why = closing ? "the bridge stops" : e.getMessage();
    } catch (IOException e) {
      why = e.getMessage();
    } catch (RuntimeException e) {
      why = "internal error: " + e;
    } finally {
      closeQuietly(s);
      synchronized (this) {
        client = null;
        clientThread = null;
      }
      log.info("palp bridge: client " + s.getRemoteSocketAddress() + " disconnected: " + why);
      listener.connectionClosed();
    }
  }

  /** The response PDU to a request PDU (function code first). */
  byte[] handle(byte[] pdu) {
    final int function = pdu[0] & 0xFF;
    try {
      switch (function) {
        case 3: {
          need(pdu, 5);
          int count = u16(pdu, 3);
          int[] regs = store.read(u16(pdu, 1), count);
          byte[] r = new byte[2 + 2 * regs.length];
          r[0] = 3;
          r[1] = (byte) (2 * regs.length);
          for (int i = 0; i < regs.length; ++i) put16(r, 2 + 2 * i, regs[i]);
          return r;
        }
        case 6: {
          need(pdu, 5);
          store.write(u16(pdu, 1), new int[] {u16(pdu, 3)});
          return copy(pdu, 5);
        }
        case 16: {
          need(pdu, 6);
          int count = u16(pdu, 3);
          int bytes = pdu[5] & 0xFF;
          if (count < 1 || count > RegisterMap.MAX_WRITE_REGISTERS || bytes != 2 * count || pdu.length != 6 + bytes)
            throw new ModbusException(ModbusException.ILLEGAL_DATA_VALUE, "FC16 of " + count + " registers with "
                + bytes + " bytes counted and " + (pdu.length - 6) + " sent");
          int[] values = new int[count];
          for (int i = 0; i < count; ++i) values[i] = u16(pdu, 6 + 2 * i);
          store.write(u16(pdu, 1), values);
          return copy(pdu, 5);
        }
        default:
          throw new ModbusException(ModbusException.ILLEGAL_FUNCTION, "function code " + function);
      }
    } catch (ModbusException e) {
      return new byte[] {(byte) (function | 0x80), (byte) e.code()};
    } catch (RuntimeException e) {
      log.info("palp bridge: internal error serving function " + function + ": " + e);
      return new byte[] {(byte) (function | 0x80), (byte) ModbusException.SERVER_DEVICE_FAILURE};
    }
  }

  private static void need(byte[] pdu, int length) throws ModbusException {
    if (pdu.length < length)
      throw new ModbusException(ModbusException.ILLEGAL_DATA_VALUE, "request of " + pdu.length + " bytes, expected "
          + length);
  }

  private static byte[] copy(byte[] pdu, int n) {
    byte[] r = new byte[n];
    System.arraycopy(pdu, 0, r, 0, n);
    return r;
  }

  private static int u16(byte[] b, int at) {
    return ((b[at] & 0xFF) << 8) | (b[at + 1] & 0xFF);
  }

  private static void put16(byte[] b, int at, int v) {
    b[at] = (byte) (v >> 8);
    b[at + 1] = (byte) v;
  }

  private static void closeQuietly(ServerSocket c) {
    try {
      c.close();
    } catch (IOException e) {
      // closing: nothing left to do
    }
  }

  private static void closeQuietly(Socket s) {
    try {
      s.close();
    } catch (IOException e) {
      // closing: nothing left to do
    }
  }

  private static void join(Thread t) {
    try {
      t.join(2000);
    } catch (InterruptedException e) {
      Thread.currentThread().interrupt();
    }
  }
}
