// Calling the vorogeo runtime from C# through P/Invoke, the way a Unity native plugin
// does: the blob and the graph memory are unmanaged buffers the host owns.
//   mcs -out:VorogeoExample.exe VorogeoExample.cs
//   LD_LIBRARY_PATH=<prefix>/lib mono VorogeoExample.exe BLOB.vgeo
using System;
using System.IO;
using System.Runtime.InteropServices;

static class Vorogeo
{
    const string Lib = "vorogeo";  // libvorogeo.so / vorogeo.dll / libvorogeo.dylib

    [DllImport(Lib)] public static extern IntPtr vg_status_string(int status);
    [DllImport(Lib)] public static extern IntPtr vg_version_string();
    [DllImport(Lib)] public static extern int vg_open_size(IntPtr blob, UIntPtr blobSize, out UIntPtr need);
    [DllImport(Lib)] public static extern int vg_open(IntPtr blob, UIntPtr blobSize, IntPtr memory, UIntPtr memorySize,
                                                      out IntPtr graph);
    [DllImport(Lib)] public static extern uint vg_vertex_count(IntPtr graph);
    [DllImport(Lib)] public static extern UIntPtr vg_workspace_size(IntPtr graph);
    [DllImport(Lib)] public static extern int vg_workspace_init(IntPtr graph, IntPtr memory, UIntPtr size,
                                                                out IntPtr workspace);
    [DllImport(Lib)] public static extern int vg_distance(IntPtr graph, IntPtr workspace, uint source, uint target,
                                                          out float distance);
    [DllImport(Lib)] public static extern int vg_distance_field(IntPtr graph, IntPtr workspace, uint[] sources,
                                                                UIntPtr sourceCount, float[] distances);

    public static void Check(int status, string what)
    {
        if (status != 0)
            throw new Exception(what + ": " + Marshal.PtrToStringAnsi(vg_status_string(status)));
    }
}

static class Program
{
    static int Main(string[] args)
    {
        if (args.Length != 1) { Console.Error.WriteLine("usage: VorogeoExample.exe BLOB.vgeo"); return 2; }
        byte[] bytes = File.ReadAllBytes(args[0]);
        IntPtr blob = Marshal.AllocHGlobal(bytes.Length);
        Marshal.Copy(bytes, 0, blob, bytes.Length);
        try
        {
            Console.WriteLine("vorogeo " + Marshal.PtrToStringAnsi(Vorogeo.vg_version_string()) + " from C#");
            UIntPtr need;
            Vorogeo.Check(Vorogeo.vg_open_size(blob, (UIntPtr)bytes.Length, out need), "vg_open_size");
            IntPtr memory = Marshal.AllocHGlobal((IntPtr)(long)need.ToUInt64());
            IntPtr graph;
            Vorogeo.Check(Vorogeo.vg_open(blob, (UIntPtr)bytes.Length, memory, need, out graph), "vg_open");
            UIntPtr wsSize = Vorogeo.vg_workspace_size(graph);
            IntPtr wsMemory = Marshal.AllocHGlobal((IntPtr)(long)wsSize.ToUInt64());
            IntPtr ws;
            Vorogeo.Check(Vorogeo.vg_workspace_init(graph, wsMemory, wsSize, out ws), "vg_workspace_init");

            uint n = Vorogeo.vg_vertex_count(graph);
            float d;
            Vorogeo.Check(Vorogeo.vg_distance(graph, ws, 0, n / 2, out d), "vg_distance");
            Console.WriteLine(string.Format(System.Globalization.CultureInfo.InvariantCulture,
                                            "distance 0 -> {0} = {1:F5}", n / 2, d));
            float[] field = new float[n];
            Vorogeo.Check(Vorogeo.vg_distance_field(graph, ws, new uint[] { 0 }, (UIntPtr)1, field), "vg_distance_field");
            Console.WriteLine(string.Format(System.Globalization.CultureInfo.InvariantCulture,
                                            "field at {0} = {1:F5}", n / 2, field[n / 2]));
            Marshal.FreeHGlobal(wsMemory);
            Marshal.FreeHGlobal(memory);  // ends the graph
        }
        catch (Exception e)
        {
            Console.Error.WriteLine("VorogeoExample: " + e.Message);
            return 1;
        }
        finally
        {
            Marshal.FreeHGlobal(blob);
        }
        return 0;
    }
}
